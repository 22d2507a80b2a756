"""Start joint angles of the physics twin (``sim_robot ~joints``): checked, then placed where they fit.

The twin builds the robot lying straight on the pipe floor. Bent start
angles set on that robot would mostly put a module inside the wall: a
front module tilted 1.2 rad in a 90 mm pipe sits 21 mm deep, a rear V at
its clamp angles 11 mm. MuJoCo then throws the robot out of the wall,
and the run starts from a pose no robot can be in (seen: bends past their
stops, a clamp reported on a robot jammed that way). So the angles are
checked (known joint, a number, within the joint's range) and the robot
is moved across the pipe (never along it, never rolled), pitched if it
must, to the nearest place where nothing is deeper in a wall than
:data:`FIT_TOLERANCE_M`, level first; gravity then settles it from there
(:class:`pirate.sim.twin.TwinRobot`). A pose that fits nowhere is refused,
naming the module and how deep it would be.
"""
import math

import mujoco
import numpy

#: Deeper than this into a wall is not a pose the robot can be in, m
#: (a resting wheel's contact is within 0.1 mm).
FIT_TOLERANCE_M = 0.001
#: Spacing of the places tried across the pipe, m.
SEARCH_STEP_M = 0.002
#: Pitches tried (robot's left axis), rad, level first: a bent robot rests on
#: the floor with its axis tilted (a rear module bent down lifts the middle).
PITCHES_RAD = sorted((0.05 * k for k in range(-8, 9)), key=lambda p: (abs(p), p))


class StartPoseError(ValueError):
    """A start pose the twin cannot start from; the message says why."""


def poseable_joints(model, stops=None):
    """{joint name: (low, high) rad} of every joint a start pose may set:
    the robot's hinges but the wheels (their angle is odometry, not pose),
    each within the model's range or ``stops`` (name -> (low, high)) where
    the joint's own board stops it short of that (the front tilt)."""
    joints = {}
    for j in range(model.njnt):
        joint = model.joint(j)
        if joint.type[0] != mujoco.mjtJoint.mjJNT_HINGE or joint.name.startswith('wheel_'):
            continue
        low, high = joint.range if model.jnt_limited[j] else (-math.pi, math.pi)
        joints[joint.name] = tuple(float(v) for v in (stops or {}).get(joint.name, (low, high)))
    return joints


def check(joints, known):
    """``joints`` (name -> rad) as floats, or :class:`StartPoseError` for a
    joint not in ``known`` (:func:`poseable_joints`), a value that is not a
    number, or one outside the joint's range."""
    if not isinstance(joints, dict):
        raise StartPoseError('start joints %r: a dict of joint name -> rad is needed' % (joints,))
    checked = {}
    for name, value in joints.items():
        if name not in known:
            raise StartPoseError('start joint %r: not a joint of the robot; use %s' % (name, ', '.join(sorted(known))))
        try:
            angle = float(value)
        except (TypeError, ValueError):
            raise StartPoseError('start joint %s: %r is not a number of rad' % (name, value))
        low, high = known[name]
        if not (low <= angle <= high):      # also refuses nan
            raise StartPoseError('start joint %s: %r rad is outside its range %.2f..%.2f rad'
                                 % (name, value, low, high))
        checked[name] = angle
    return checked


def deepest(model, data, root_body):
    """(depth m, robot body) of the robot's deepest contact, (0, None) when
    no part of the robot (the tree under ``root_body``) is inside a wall or
    debris. Debris on a wall is not the robot's business."""
    count = data.ncon
    if not count:
        return 0.0, None
    owners = model.geom_bodyid[data.contact.geom[:count]]             # (contacts, 2) bodies
    robot = model.body_rootid[owners] == model.body(root_body).id
    depth = numpy.where(robot.any(axis=1), -data.contact.dist[:count], 0.0)
    worst = int(depth.argmax())
    if depth[worst] <= 0.0:
        return 0.0, None
    return float(depth[worst]), model.body(int(owners[worst][robot[worst]][0])).name


def _places(start, axis_point, across, inside_m):
    """Root positions to try, world: ``start`` first, then a grid in the
    cross-section through it, nearest first, within ``inside_m`` of the
    pipe's axis (so the robot is never put outside the pipe, where nothing
    is in its way)."""
    left, up = numpy.asarray(across[0], dtype=float), numpy.asarray(across[1], dtype=float)
    start = numpy.asarray(start, dtype=float)
    centre = start - left * numpy.dot(start - axis_point, left) - up * numpy.dot(start - axis_point, up)
    steps = int(inside_m / SEARCH_STEP_M)
    grid = [centre + SEARCH_STEP_M * (i * left + j * up) for i in range(-steps, steps + 1)
            for j in range(-steps, steps + 1) if math.hypot(i, j) * SEARCH_STEP_M <= inside_m]
    return [start] + sorted(grid, key=lambda p: float(numpy.linalg.norm(p - start)))


def _pitched(quat, pitch):
    """``quat`` (w x y z) turned by ``pitch`` rad about the robot's own left (y) axis."""
    turn = numpy.array((math.cos(pitch / 2), 0.0, math.sin(pitch / 2), 0.0))
    out = numpy.zeros(4)
    mujoco.mju_mulQuat(out, numpy.asarray(quat, dtype=float), turn)
    return out


def _fits(model, data, root_body):
    mujoco.mj_kinematics(model, data)
    mujoco.mj_collision(model, data)
    return deepest(model, data, root_body)


def place(model, data, joints, root_joint, bore, stops=None):
    """Set ``joints`` (checked against :func:`poseable_joints` with ``stops``)
    and move the robot's free ``root_joint`` across the pipe, and pitch it if
    it must, until the pose fits. ``bore`` = (a point on the pipe's axis,
    (left, up) unit vectors of its cross-section, how far from the axis the
    root may be, m), all world. Level and near first. Returns (move m, pitch
    rad) or raises :class:`StartPoseError`."""
    axis_point, across, inside_m = bore
    joints = check(joints if joints is not None else {}, poseable_joints(model, stops))
    for name, angle in joints.items():
        data.qpos[model.jnt_qposadr[model.joint(name).id]] = angle
    mujoco.mj_forward(model, data)
    if not joints:
        return numpy.zeros(3), 0.0
    root_body = model.body(model.jnt_bodyid[model.joint(root_joint).id]).name
    address = model.jnt_qposadr[model.joint(root_joint).id]
    position, orientation = slice(address, address + 3), slice(address + 3, address + 7)
    root, quat = data.qpos[position].copy(), data.qpos[orientation].copy()
    best, places = None, _places(root, axis_point, across, inside_m)
    for pitch in PITCHES_RAD:
        data.qpos[orientation] = _pitched(quat, pitch)
        for spot in places:
            data.qpos[position] = spot
            depth, body = _fits(model, data, root_body)
            if depth <= FIT_TOLERANCE_M:
                mujoco.mj_forward(model, data)
                return spot - root, pitch
            if best is None or depth < best[0]:
                best = (depth, body)
    data.qpos[position], data.qpos[orientation] = root, quat
    mujoco.mj_forward(model, data)
    raise StartPoseError('start joints %s do not fit in the pipe: wherever the robot is put across it (pitched up to '
                         '%.1f rad, at this roll), the %s is at least %.0f mm inside the wall' % (
                             ', '.join('%s %.2f' % item for item in sorted(joints.items())), max(PITCHES_RAD),
                             part_name(best[1]), best[0] * 1000))


def part_name(body):
    """The robot's word for a twin body: 'wheel_body_22' -> 'wheel of board 22',
    'bend_iv_module' -> 'Bend IV module'."""
    if body.startswith('wheel_body_'):
        return 'wheel of board %s' % body[len('wheel_body_'):]
    words = body.split('_')
    return ' '.join(w.upper() if w in ('i', 'ii', 'iii', 'iv') else w for w in words).replace('bend', 'Bend', 1)
