"""The physics twin: generated models load, the
robot matches the module table, the pipe is hollow with a real mitre
corner and an open T side, each board's modes act as the boards do, the
sensors are raw and quantised, gravity settles the robot, and a clamp
reaches the angle the report's geometry predicts (derived here)."""
import math
import os
import xml.etree.ElementTree as ET

import mujoco
import numpy
import pytest

from pirate import paths
from pirate.robot import safety, tables, units
from pirate.sim import twin_model, twin_pipes, twin_robot
from pirate.sim.twin import TwinRobot
from pirate.world import network

WORLDS = os.path.join(paths.CONFIG_DIR, 'worlds')
L_M, WHEEL_D_M = 0.09, 0.046          # report 2.4.1.1: l, D_w
CODE, COMMAND = safety.MODE_CODES, safety.COMMAND_CODES
UPRIGHT = math.pi / 2


def world(name):
    return os.path.join(WORLDS, name + '.yaml')


def arrays(setpoints=None, modes=None, limits=None, command='play'):
    """The three arrays as the laptop sends them (by element name)."""
    sp, md, lm = [0] * tables.SETPOINT_SIZE, [CODE['pwm']] * tables.CONTROL_SIZE, [safety.NO_LIMIT] * 4
    md[tables.element('rotation').index] = CODE['position']
    for name, value in (setpoints or {}).items():
        sp[tables.element(name).index] = value
    for name, mode in (modes or {}).items():
        md[tables.element(name).index] = CODE[mode]
    for name, value in (limits or {}).items():
        lm[tables.limit_index(name)] = value
    md[tables.element('rear_module').index] = COMMAND[command]
    return sp, md, lm


TORQUE = {b: 'torque' for b in tables.BEND_JOINTS}


def run_until(robot, condition, limit_s):
    """Step 0.1 s at a time until ``condition(robot)``; robot seconds taken."""
    t = 0.0
    while not condition(robot) and t < limit_s:
        robot.step(0.1)
        t += 0.1
    return t


#: Clamp guards (outer, inner), report Table 5.2.
GUARDS = {90: (-0.77, 0.35), 110: (-1.25, 0.65)}
#: Move front (nominal) guard, Table 5.3: the front module clear of the floor.
FRONT_LIFT = {90: 0.4, 110: 0.7}


def clamp(robot, part, diameter=90):
    """As the clamp primitive does it: torque until the guards, then the
    inner bend released (setpoint 0); angles once it has come to rest."""
    outer, inner = ('bend_iv', 'bend_iii') if part == 'rear' else ('bend_i', 'bend_ii')
    sp = {outer: 256, inner: -256}
    if part == 'front':
        sp.update(bend_iv=256)
    robot.command(*arrays(sp, TORQUE))
    guard_outer, guard_inner = GUARDS[diameter]
    run_until(robot, lambda r: r.angle(outer) <= guard_outer and r.angle(inner) >= guard_inner, 15.0)
    sp[inner] = 0
    robot.command(*arrays(sp, TORQUE))
    run_until(robot, lambda r: False, 3.0)
    return robot.angle(outer), robot.angle(inner)


@pytest.mark.parametrize('name', ['straight_90', 'straight_110', 'network_90'])
def test_every_world_generates_a_model_mujoco_loads(name):
    robot = TwinRobot(world(name))
    model = robot.model
    assert model.ngeom > 30 and model.nu == 4 + 3 + 1 + len(tables.DRIVE_BOARDS)
    for joint in tables.JOINT_NAMES:
        assert model.joint(joint) is not None


def test_contacts_are_found_alike_in_every_mujoco_from_3_2_3():
    """MuJoCo's own convex collision detection with 35 iterations, in 3.2.3
    (where it is opt-in and 50 is the default) as in 3.3 and later (where
    both are the defaults): with libccd the twin's front wheel spun past
    its speed limit steering into a mitre bend."""
    options = TwinRobot(world('straight_90'), settle_s=0.0).model.opt
    if hasattr(mujoco.mjtEnableBit, 'mjENBL_NATIVECCD'):        # before 3.3: opt-in
        assert options.enableflags & mujoco.mjtEnableBit.mjENBL_NATIVECCD
    else:
        assert not options.disableflags & mujoco.mjtDisableBit.mjDSBL_NATIVECCD
    assert options.ccd_iterations == 35


def test_obstacles_are_in_the_model_and_debris_falls_to_the_floor():
    straight = {'type': 'straight', 'length_mm': 1000}
    net = network.build({'pieces': [straight], 'start': {'at_mm': 300}, 'obstacles': [
        {'type': 'step', 'at_mm': 600, 'height_mm': 4},
        {'type': 'reduction', 'at_mm': 800, 'diameter_mm': 80},
        {'type': 'debris', 'at_mm': 700, 'size_mm': 6}]})
    robot = TwinRobot(net, settle_s=1.0)
    names = [robot.model.geom(g).name for g in range(robot.model.ngeom)]
    assert any(n.startswith('step') for n in names)
    debris = [robot.model.body(b).name for b in range(robot.model.nbody) if robot.model.body(b).name.startswith('debris')]
    assert len(debris) == 1
    robot.step(1.0)
    assert -0.045 < robot.body_pose(debris[0])[0][2] < -0.035                   # resting on the floor
    assert numpy.abs(robot.data.body(debris[0]).cvel).max() < 0.01
    assert _ray(robot, (0.825, 0.0, 0.0), (0.0, 0.0, 1.0)) == pytest.approx(0.040, abs=0.001)  # narrower



def test_resting_debris_stays_until_the_robot_pushes_it():
    """Debris at rest stays put; the robot driving into it pushes it along
    the floor."""
    net = network.build({'pieces': [{'type': 'straight', 'length_mm': 1500}], 'start': {'at_mm': 400},
                         'obstacles': [{'type': 'debris', 'at_mm': 760, 'size_mm': 6}]})
    robot = TwinRobot(net, settle_s=1.0)
    debris = robot.model.body([robot.model.body(b).name for b in range(robot.model.nbody)
                               if robot.model.body(b).name.startswith('debris')][0])
    start = robot.data.xpos[debris.id].copy()
    robot.step(0.5)
    assert numpy.abs(robot.data.xpos[debris.id] - start).max() < 0.0005          # at rest
    robot.command(*arrays({'wheels': units.mm_s_to_wheel_counts(100.0)}, {'wheels': 'velocity'}))
    run_until(robot, lambda r: r.data.xpos[debris.id][0] - start[0] > 0.05, 6.0)
    assert robot.data.xpos[debris.id][0] - start[0] > 0.05                       # pushed


def test_robot_geometry_matches_the_module_table():
    robot = TwinRobot(world('straight_90'), settle_s=0.0)
    model, data = robot.model, robot.data
    pitch = ['front_tilt', 'bend_i', 'bend_ii', 'bend_iii', 'bend_iv', 'rear_tilt']
    anchors = [data.xanchor[model.joint(j).id] for j in pitch]
    gaps = [numpy.linalg.norm(a - b) for a, b in zip(anchors, anchors[1:])]
    assert gaps == pytest.approx([L_M] * 5, abs=1e-9)       # Bend II..III span the rotational module
    wheels = [g for g in range(model.ngeom) if model.geom(g).name.startswith('wheel_geom_')]
    assert sorted(int(model.geom(g).name[-2:]) for g in wheels) == sorted(tables.DRIVE_BOARDS)
    assert all(model.geom_size[g][0] == pytest.approx(WHEEL_D_M / 2) for g in wheels)
    shells = [model.geom(g).name for g in range(model.ngeom) if model.geom(g).name.endswith('_shell')]
    assert len(shells) == 8                                  # 7 modules, the rotational in two halves
    assert sum(model.body_mass) == pytest.approx(sum(model.body_mass[1:]))  # the world has none


def _ray(robot, origin, direction):
    """Distance to the first pipe geom along ``direction`` (-1: none)."""
    geomid = numpy.array([-1], dtype=numpy.int32)
    group = numpy.zeros(6, dtype=numpy.uint8)
    group[twin_pipes.PIPE_GROUP] = 1
    return mujoco.mj_ray(robot.model, robot.data, numpy.array(origin, float), numpy.array(direction, float),
                         group, 1, -1, geomid)


def test_pipe_is_hollow_the_mitre_corner_is_there_and_the_tee_side_open():
    net = network.load(world('network_90'))
    robot = TwinRobot(net, settle_s=0.0)
    radius = 0.045
    wall = radius / math.cos(math.pi / 24)                  # a flat segment's corner
    for phi in numpy.linspace(0, 2 * math.pi, 13):
        hit = _ray(robot, (0.5, 0.0, 0.0), (0.0, math.cos(phi), math.sin(phi)))
        assert radius - 1e-6 <= hit <= wall + 1e-6
    mitre, tee = net.pieces[1], net.pieces[3]
    corner = numpy.add(mitre.entry.origin, numpy.multiply(mitre.entry.axes[0], radius))
    # Straight on through the mitre: its outer wall stops the ray within the bend.
    assert 0 < _ray(robot, corner, mitre.entry.axes[0]) <= radius * 1.1
    # Back along the way in: the straight is clear to its open start.
    assert _ray(robot, corner, numpy.negative(mitre.entry.axes[0])) == -1
    tee_centre = numpy.add(tee.entry.origin, numpy.multiply(tee.entry.axes[0], radius))
    assert _ray(robot, tee_centre, tee.stub.axes[0]) == -1   # the branch is open
    assert 0 < _ray(robot, tee_centre, numpy.negative(tee.stub.axes[0])) <= wall + 1e-6


def test_tee_entered_through_its_branch_is_open_at_the_far_run_end():
    straight = {'type': 'straight', 'length_mm': 500}
    net = network.build({'pieces': [straight, {'type': 'tee', 'enter': 'branch', 'side': 'left'}, straight]})
    robot = TwinRobot(net, settle_s=0.0)
    tee, radius = net.pieces[1], 0.045
    centre = numpy.add(tee.entry.origin, numpy.multiply(tee.entry.axes[0], radius))
    assert _ray(robot, centre, tee.stub.axes[0]) == -1                    # the far run end is open
    assert _ray(robot, centre, tee.exit.axes[0]) == -1                    # on into the next straight (open end)
    assert _ray(robot, centre, tee.entry.axes[0]) == pytest.approx(radius, abs=0.004)   # the run's wall ahead
    assert _ray(robot, centre, numpy.negative(tee.entry.axes[0])) == -1   # back down the branch


@pytest.mark.parametrize('side', ['left', 'right'])
def test_tee_entered_through_its_run_and_left_by_its_branch_is_open_ahead_and_the_branch_is_there(side):
    straight = {'type': 'straight', 'length_mm': 500}
    net = network.build({'pieces': [straight, {'type': 'tee', 'enter': 'run', 'side': side, 'leave': 'branch'},
                                    straight]})
    robot = TwinRobot(net, settle_s=0.0)
    tee, radius = net.pieces[1], 0.045
    wall = radius / math.cos(math.pi / 24)                  # a flat segment's corner
    centre = numpy.add(tee.entry.origin, numpy.multiply(tee.entry.axes[0], radius))
    assert _ray(robot, centre, tee.stub.axes[0]) == -1                    # the run's far end, ahead, is open
    assert _ray(robot, centre, tee.exit.axes[0]) == -1                    # on into the branch and its straight
    assert 0 < _ray(robot, centre, numpy.negative(tee.exit.axes[0])) <= wall + 1e-6   # the run's wall opposite
    assert _ray(robot, centre, numpy.negative(tee.entry.axes[0])) == -1   # back down the run
    # The branch is a pipe, not a hole: its walls stand beside the way out, off the run.
    in_branch = numpy.add(tee.exit.origin, numpy.multiply(tee.exit.axes[0], 0.02))
    for across in (tee.exit.axes[1], numpy.negative(tee.exit.axes[1]), tee.exit.axes[2]):
        assert radius - 1e-6 <= _ray(robot, in_branch, across) <= wall + 1e-6
    # The run goes on past the hole: its wall stands above and below the axis ahead.
    ahead = numpy.add(centre, numpy.multiply(tee.entry.axes[0], 1.5 * radius))
    for across in (tee.entry.axes[2], numpy.negative(tee.entry.axes[2])):
        assert radius - 1e-6 <= _ray(robot, ahead, across) <= wall + 1e-6


@pytest.mark.parametrize('name, diameter, bore_mm', [
    ('straight_90', 90, 90.0), ('straight_110', 110, 110.0), ('straight_90_sdr26', 90, 83.0)])
def test_clamp_reaches_the_angle_the_geometry_predicts(name, diameter, bore_mm):
    """In the world's bore: a plain pipe's diameter, a real pipe's (its wall inside its size)."""
    apex = math.asin((bore_mm / 1000.0 - WHEEL_D_M) / L_M)   # eq 2.1: the V's apex wheel on the wall
    robot = TwinRobot(world(name))
    assert robot.pipe_diameter_m == pytest.approx(bore_mm / 1000.0)
    robot.command(*arrays({'front_tilt': 32}))
    lift = FRONT_LIFT[diameter]
    run_until(robot, lambda r: r.angle('front_tilt') >= lift, 10.0)
    outer, inner = clamp(robot, 'rear', diameter)
    assert inner == pytest.approx(apex, abs=0.03) and outer == pytest.approx(-2 * apex, abs=0.05)
    outer, inner = clamp(robot, 'front', diameter)
    assert inner == pytest.approx(apex, abs=0.03) and outer == pytest.approx(-2 * apex, abs=0.05)
    assert {23, 26} <= set(robot.wheel_contacts())           # both apex wheels on the wall


def test_bend_pwm_moves_with_the_duty_and_the_worm_holds_at_zero():
    robot = TwinRobot(world('straight_90'))
    robot.command(*arrays({'bend_iii': -256}))
    run_until(robot, lambda r: False, 1.5)
    lifted = robot.angle('bend_iii')
    assert lifted > 0.05                                      # negative duty opens an inner bend upwards
    robot.command(*arrays({'bend_iii': 0}))
    robot.step(0.2)
    held = robot.angle('bend_iii')
    run_until(robot, lambda r: False, 10.0)                   # gravity pulls the lifted modules down
    assert robot.angle('bend_iii') == pytest.approx(held, abs=0.01)


def test_torque_mode_spring_reaches_the_setpoint_within_its_limit():
    robot = TwinRobot(world('straight_90'))
    robot.command(*arrays({'bend_iv': 256, 'bend_iii': -256}, TORQUE, limits={'bend_iv': 150}))
    run_until(robot, lambda r: False, 8.0)
    limited = robot.small_state(27)[tables.SS_BEND_LOAD]
    assert limited == pytest.approx(150, abs=20)             # held at the limit, in spring counts
    robot.command(*arrays({'bend_iv': 256, 'bend_iii': -256}, TORQUE))
    run_until(robot, lambda r: False, 3.0)
    assert robot.small_state(27)[tables.SS_BEND_LOAD] == pytest.approx(256, abs=20)


def test_position_modes_converge_front_tilt_camera_rotation():
    robot = TwinRobot(world('straight_90'))
    target = units.rad_to_encoder(0.3)
    robot.command(*arrays({'front_tilt': target, 'camera_tilt': -target},
                          {'front_tilt': 'position', 'camera_tilt': 'position'}))
    run_until(robot, lambda r: False, 6.0)
    assert robot.angle('front_tilt') == pytest.approx(0.3, abs=0.02)
    assert robot.angle('camera_tilt') == pytest.approx(-0.3, abs=0.02)


def test_rotation_turns_the_unclamped_part_only():
    robot = TwinRobot(world('straight_90'))
    robot.command(*arrays({'front_tilt': 32}))
    run_until(robot, lambda r: r.angle('front_tilt') >= 0.4, 10.0)
    clamp(robot, 'rear')
    rear_roll = robot.roll()
    sp = {'bend_iv': 256, 'bend_iii': 0, 'rotation': units.rad_to_rotation(0.3)}
    robot.command(*arrays(sp, TORQUE))
    run_until(robot, lambda r: False, 4.0)
    assert robot.roll() == pytest.approx(rear_roll, abs=0.03)          # the clamped rear stays
    assert robot.roll(twin_robot.ROTATIONAL_FRONT) == pytest.approx(rear_roll - 0.3, abs=0.05)
    assert robot.small_state(tables.ROTATION_BOARD)[tables.SS_ANGLE] == pytest.approx(
        units.rad_to_rotation(0.3), abs=60)



def _custom_clamp(robot, setpoints, outer, inner):
    """Torque to Table 5.3's custom guards, then the inner bend released."""
    setpoints.update({outer: 256, inner: -256})
    robot.command(*arrays(setpoints, TORQUE))
    run_until(robot, lambda r: r.angle(outer) <= -0.68 and r.angle(inner) >= 0.33, 15.0)
    setpoints[inner] = 0
    robot.command(*arrays(setpoints, TORQUE))
    run_until(robot, lambda r: False, 0.5)


def _rear_roll_while_the_front_turns(timestep_s):
    """bench/sim_twin_figures item 5: released at 0.9 rad, both parts
    custom-clamped, the front partially unclamped and held by its worms,
    then turned +0.7 -> -0.7 rad: the clamped rear's roll change, rad."""
    config = twin_model.load_config()
    config['physics']['timestep_s'] = timestep_s
    robot = TwinRobot(world('straight_90'), orientation=0.9, config=config)
    sp = {'rotation': units.rad_to_rotation(0.7), 'front_tilt': 32}
    robot.command(*arrays(sp, TORQUE))
    run_until(robot, lambda r: r.angle('front_tilt') >= 0.3 and r.time >= 5.0, 15.0)
    sp['front_tilt'] = 0
    _custom_clamp(robot, sp, 'bend_iv', 'bend_iii')
    _custom_clamp(robot, sp, 'bend_i', 'bend_ii')
    sp.update(bend_i=-100, bend_ii=150)
    robot.command(*arrays(sp, TORQUE))
    run_until(robot, lambda r: r.angle('bend_i') >= -0.48 and r.angle('bend_ii') <= 0.29, 15.0)
    sp.update(bend_i=0, bend_ii=0, rotation=units.rad_to_rotation(-0.7))
    before = robot.roll()
    robot.command(*arrays(sp, dict(TORQUE, bend_i='pwm', bend_ii='pwm')))
    run_until(robot, lambda r: False, 8.0)
    return robot.roll() - before


def test_the_clamped_parts_roll_while_the_other_turns_does_not_depend_on_the_step():
    """The rotation turns the front against the rear's clamp through its
    clipped torque only. With the motor's damping as the servo's kv,
    MuJoCo's implicit step applied it beyond the clip, more the longer the
    step: here the rear rolled -0.055 rad at 1 ms and -0.098 at 2 ms
    (bench/sim_twin_figures item 5: -0.124 / -0.318, and -0.085 at
    0.25 ms); as the joint's damping -0.046 / -0.033
    (measurements.md#twin-rotation-damping)."""
    rolled = [_rear_roll_while_the_front_turns(step) for step in (0.001, 0.002)]
    assert rolled[0] == pytest.approx(rolled[1], abs=0.02), rolled
    assert abs(rolled[0]) < 0.1, rolled

def test_wheels_follow_velocity_and_slip_shows_in_odometry():
    """Unclamped, the apex wheels (mirrored, tables.WHEEL_SIGN) touch the
    floor and turn against the others: they slip, and their encoders count
    turns the robot never travelled. Rolling with the robot, a mirrored
    wheel's encoder would count minus the travel; a slipping one counts
    anything else (how far toward its setpoint it gets is the friction
    balance, not the slip)."""
    robot = TwinRobot(world('straight_90'))
    counts = units.mm_s_to_wheel_counts(100.0)
    start = robot.body_pose(twin_robot.ROOT)[0][0]
    robot.command(*arrays({'wheels': counts}, {'wheels': 'velocity'}))
    run_until(robot, lambda r: False, 2.0)
    travel_mm = (robot.body_pose(twin_robot.ROOT)[0][0] - start) * 1000
    odometry_mm = {b: units.odometry_to_mm(robot.small_state(b)[tables.SS_ODOMETRY]) for b in tables.DRIVE_BOARDS}
    assert travel_mm == pytest.approx(100.0 * 2.0, rel=0.1)             # at its setpoint: the PI loop (boards.WheelBoard)
    assert odometry_mm[22] == pytest.approx(travel_mm, rel=0.1)         # Bend I's wheel rolls
    rolling_mm = {b: tables.WHEEL_SIGN[b] * travel_mm for b in (23, 26)}
    assert all(abs(odometry_mm[b] - rolling_mm[b]) > 0.25 * travel_mm for b in (23, 26))  # both slip


def test_nothing_moves_before_play_or_after_stop():
    robot = TwinRobot(world('straight_90'))
    before = {j: robot.angle(j) for j in tables.BEND_JOINTS}
    robot.command(*arrays({'bend_iii': -256, 'front_tilt': 100}, command='stop'))
    run_until(robot, lambda r: False, 2.0)
    assert {j: robot.angle(j) for j in tables.BEND_JOINTS} == pytest.approx(before, abs=0.005)


def test_small_state_is_raw_and_quantised():
    robot = TwinRobot(world('straight_90'), orientation=1.2)
    for board in tables.BOARDS:
        state = robot.small_state(board)
        assert len(state) == tables.SMALL_STATE_SIZE
        assert all(isinstance(v, int) and -32768 <= v <= 32767 for v in state)
    assert robot.small_state(22)[tables.SS_ANGLE] == units.rad_to_encoder(robot.angle('bend_i'))
    imu = robot.small_state(tables.IMU_BOARD)
    roll = units.gravity_to_roll(imu[tables.SS_IMU_Y], imu[tables.SS_IMU_Z])
    assert roll == pytest.approx(robot.roll(), abs=1e-3)
    with pytest.raises(KeyError):
        robot.small_state(99)


def test_imu_rates_are_the_rear_parts_own_in_a_world_with_debris():
    robot = TwinRobot(world('network_90'), orientation=0.6, settle_s=0.0)   # debris' free joint comes first
    robot.step(0.06)                                                         # falling and rolling
    imu = robot.small_state(tables.IMU_BOARD)
    rates = [imu[i] for i in (tables.SS_IMU_U, tables.SS_IMU_V, tables.SS_IMU_W)]
    mujoco.mj_forward(robot.model, robot.data)   # cvel and xmat of the state the IMU read (qvel unchanged)
    body = robot.data.body(twin_robot.ROOT)
    rot = body.xmat.reshape(3, 3)
    expected = rot.T @ body.cvel[:3]        # world -> rear-part frame
    assert rates == pytest.approx([math.degrees(w) * units.IMU_COUNTS_PER_DEG_S for w in expected], abs=1)
    assert max(abs(r) for r in rates) > 10


def test_sensor_noise_is_seeded():
    def reads(seed):
        robot = TwinRobot(world('straight_90'), seed=seed)
        return [robot.small_state(b) for b in tables.BOARDS for _ in range(3)]
    assert reads(7) == reads(7)
    assert reads(7) != reads(8)
    quiet = TwinRobot(world('straight_90'))
    assert quiet.small_state(25) == quiet.small_state(25)


def test_each_angle_sensor_reads_with_its_own_constant_offset_within_the_bound():
    config = twin_model.load_config()
    config['sensors'].update(angle_noise_counts=0.0, angle_bias_counts=10.0)

    def offsets(seed):
        robot = TwinRobot(world('straight_90'), seed=seed, config=config)
        return [robot.small_state(joint.board)[tables.SS_ANGLE] - units.rad_to_encoder(robot.angle(joint.name))
                for joint in tables.JOINTS if joint.name in tables.BEND_JOINTS]
    assert offsets(3) == offsets(3)
    assert all(abs(o) <= 10 for o in offsets(3)) and len(set(offsets(3) + offsets(4))) > 1
    assert offsets(None) == [0] * len(tables.BEND_JOINTS), 'no seed: no noise and no offset'


def test_a_bore_error_moves_every_wall_by_half_of_it():
    def wall_distances(bore_error_m):
        body = ET.Element('worldbody')
        twin_pipes.WallBuilder(body, thickness=0.004, bore_error=bore_error_m).network(network.load(world('straight_90')))
        centres = [[float(v) for v in geom.get('pos').split()] for geom in body.iter('geom')
                   if geom.get('name', '').startswith('wall')]
        return [math.hypot(y, z) for _, y, z in centres if math.hypot(y, z) > 0.01]     # the end cap: on the axis
    nominal, wider = wall_distances(0.0), wall_distances(0.001)
    assert nominal == pytest.approx([0.045 + 0.002] * len(nominal), abs=1e-6)
    assert [w - n for w, n in zip(wider, nominal)] == pytest.approx([0.0005] * len(nominal), abs=1e-6)


def test_in_a_real_pipe_obstacles_stand_on_its_bore_and_a_reduction_keeps_its_own():
    world = network.build({'diameter_mm': 90, 'pipe': {'outer_mm': 90, 'sdr': 26},
                           'pieces': [{'type': 'straight', 'length_mm': 1500}],
                           'obstacles': [{'type': 'step', 'at_mm': 600, 'height_mm': 4},
                                         {'type': 'reduction', 'at_mm': 900, 'diameter_mm': 80}]})
    body = ET.Element('worldbody')
    twin_pipes.WallBuilder(body, thickness=0.004, bore_error=world.bore_offset_m).network(world)
    geoms = {geom.get('name'): [float(v) for v in geom.get('pos').split()] for geom in body.iter('geom')}
    step = next(pos for name, pos in geoms.items() if name.startswith('step'))
    assert step[2] == pytest.approx(-(0.0415 - 0.002))                  # on the 83 mm bore's floor
    reduction = [math.hypot(y, z) for name, (x, y, z) in geoms.items() if name.startswith('wall') and 0.89 < x < 0.96]
    assert reduction and reduction == pytest.approx([0.040 + 0.002] * len(reduction))


@pytest.mark.parametrize('roll', [0.0, 0.8, 2.5])
def test_gravity_brings_a_released_robot_to_rest_on_the_floor(roll):
    robot = TwinRobot(world('straight_90'), orientation=roll, settle_s=0.0)
    height = robot.body_pose(twin_robot.ROOT)[0][2]
    robot.step(1.0)
    resting = robot.body_pose(twin_robot.ROOT)[0][2]
    assert resting < height - 0.001                         # it fell
    assert resting < -0.045 + 0.03                          # its axis within 30 mm of the floor
    assert numpy.abs(robot.data.qvel).max() < 0.05          # and came to rest within 1 s
