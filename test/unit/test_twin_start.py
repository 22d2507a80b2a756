"""Start joint angles of the physics twin (``sim_robot ~joints``, launch arg
``joints``): a bad one is refused with its reason, a bent pose is moved
across the pipe to where it fits instead of being started inside the wall,
and a Clamp Straight from such a pose ends clamped."""
import math
import os

import mujoco
import numpy
import pytest

from pirate import paths
from pirate.sim import robot_end, twin_model, twin_robot, twin_start
from pirate.testing.harness import SimHarness
from pirate.sim.twin import TwinRobot

STRAIGHT_90 = os.path.join(paths.CONFIG_DIR, 'worlds', 'straight_90.yaml')
STRAIGHT_110 = os.path.join(paths.CONFIG_DIR, 'worlds', 'straight_110.yaml')
UPRIGHT = math.pi / 2
REAR_V_REVERSED = {'bend_iii': -0.5, 'bend_iv': 0.5}     # the rear V bent the wrong way, apex down
APEX_WHEELS = {23, 26}
BODY_RADIUS_M = twin_model.load_config()['geometry']['body_radius_m']


def twin(joints, roll=UPRIGHT, settle_s=0.0, world=STRAIGHT_90):
    return TwinRobot(world, orientation=roll, joints=joints, settle_s=settle_s)


def depth_as_set(joints, roll=UPRIGHT):
    """How deep (m) ``joints`` put the robot into the wall where it is built, without the move."""
    robot = twin({}, roll)
    for name, angle in joints.items():
        robot.data.qpos[robot.model.jnt_qposadr[robot.model.joint(name).id]] = angle
    mujoco.mj_forward(robot.model, robot.data)
    return twin_start.deepest(robot.model, robot.data, twin_robot.ROOT)[0]


@pytest.mark.parametrize('joints, reason', [
    ({'bend_2': 0.3}, "'bend_2': not a joint of the robot; use bend_i, bend_ii"),
    ({'wheel_22': 1.0}, "'wheel_22': not a joint of the robot"),
    ({'bend_i': 'x'}, "bend_i: 'x' is not a number of rad"),
    ({'bend_i': None}, 'bend_i: None is not a number of rad'),
    ({'bend_i': float('nan')}, 'bend_i: nan rad is outside its range -1.70..1.70 rad'),
    ({'bend_iv': 1.8}, 'bend_iv: 1.8 rad is outside its range -1.70..1.70 rad'),
    ({'front_tilt': 1.5}, 'front_tilt: 1.5 rad is outside its range -0.10..1.20 rad'),     # config/twin.yaml's stop
    ('front_tilt 0.4', "start joints 'front_tilt 0.4': a dict of joint name -> rad is needed"),
])
def test_a_bad_start_joint_is_refused_with_its_reason(joints, reason):
    with pytest.raises(twin_start.StartPoseError) as refused:
        twin(joints)
    assert reason in str(refused.value)


def test_a_pose_that_fits_where_the_robot_lies_is_not_moved():
    joints = {'rotation': 0.3, 'front_tilt': 0.4, 'camera_pan': 1.0}
    robot = twin(joints)
    pos, _ = twin_model.start_pose(robot.world, robot.config, UPRIGHT)
    root = robot.model.jnt_qposadr[robot.model.joint(twin_robot.ROOT_JOINT).id]
    assert numpy.allclose(robot.data.qpos[root:root + 3], pos)
    assert {name: round(robot.angle(name), 6) for name in joints} == joints


def place(joints, roll=UPRIGHT, world=STRAIGHT_90):
    """twin_start.place on a fresh robot lying straight: (robot, move m, pitch rad)."""
    robot = twin({}, roll, world=world)
    frame = robot.world.locate(robot.world.start_m)[1]
    bore = (numpy.asarray(frame.origin), frame.axes[1:3], robot.pipe_diameter_m / 2 - BODY_RADIUS_M)
    move, pitch = twin_start.place(robot.model, robot.data, joints, twin_robot.ROOT_JOINT, bore,
                                   stops={'front_tilt': robot.config['front_tilt']['range_rad']})
    return robot, move, pitch


@pytest.mark.parametrize('roll', [UPRIGHT, 0.0])
def test_a_bent_pose_is_moved_across_the_pipe_to_where_it_fits(roll):
    assert depth_as_set(REAR_V_REVERSED, roll) > 0.015          # as set on the lying robot: 22 mm in the wall
    robot, move, pitch = place(REAR_V_REVERSED, roll)
    assert twin_start.deepest(robot.model, robot.data, twin_robot.ROOT)[0] <= twin_start.FIT_TOLERANCE_M
    axis = robot.world.locate(robot.world.start_m)[1].axes[0]
    assert numpy.linalg.norm(move) > 0.005 and abs(numpy.dot(move, axis)) < 1e-9     # across, never along
    assert pitch == 0.0                                                              # level fits: kept level
    assert robot.roll() == pytest.approx(roll, abs=1e-6)                            # and not rolled


def test_a_pose_that_fits_only_pitched_is_pitched():
    joints = {'bend_iv': -0.3, 'front_tilt': 0.4}      # the rear module bent down lifts the middle
    assert depth_as_set(joints) > 0.015
    robot, move, pitch = place(joints)
    assert pitch != 0.0
    assert twin_start.deepest(robot.model, robot.data, twin_robot.ROOT)[0] <= twin_start.FIT_TOLERANCE_M
    assert {name: robot.angle(name) for name in joints} == joints


def test_the_robot_is_never_put_outside_the_pipe():
    """Outside the wall ring nothing is in the way: a first version put this
    pose there, the robot fell through nothing, and Clamp Sideways ended in a
    false success with no wheel on any wall (bench/pab_clamp_sweep --random-joints)."""
    robot, move, _ = place({'bend_iii': 0.48, 'bend_iv': -0.27}, math.radians(147), world=STRAIGHT_110)
    frame = robot.world.locate(robot.world.start_m)[1]
    root = robot.data.body(twin_robot.ROOT).xpos - numpy.asarray(frame.origin)
    from_axis = numpy.linalg.norm(root - numpy.dot(root, frame.axes[0]) * numpy.asarray(frame.axes[0]))
    assert from_axis <= robot.pipe_diameter_m / 2 - BODY_RADIUS_M + 1e-9


def test_a_pose_that_fits_nowhere_is_refused_naming_the_part_and_the_pipe():
    with pytest.raises(twin_start.StartPoseError) as refused:
        twin({'front_tilt': 1.2})               # a 90 mm module tilted 69 deg in a 90 mm bore
    text = str(refused.value)
    assert 'front_tilt 1.20 do not fit in the pipe' in text and 'pitched up to 0.4 rad' in text
    assert 'mm inside the wall' in text
    assert '(world straight_90, 90 mm, roll 1.57 rad)' in text


def test_the_settled_robot_rests_on_the_floor_holding_the_pose():
    robot = twin(REAR_V_REVERSED, settle_s=1.0)
    assert twin_start.deepest(robot.model, robot.data, twin_robot.ROOT)[0] <= twin_start.FIT_TOLERANCE_M
    assert robot.wheel_contacts(), 'the robot came to rest on the pipe'
    for name, angle in REAR_V_REVERSED.items():
        assert robot.angle(name) == pytest.approx(angle, abs=0.1)       # worm-held, the spring gives a little


def test_clamp_straight_from_a_moved_pose_ends_clamped():
    """Set on the lying robot, this pose started 22 mm inside the wall and the clamp aborted."""
    with SimHarness(world='straight_90', orientation=UPRIGHT, joints=REAR_V_REVERSED) as h:
        reason, outcome = h.execute(h.goal(0, pipe_diameter=90))
        assert reason is None and outcome.status == 'succeeded', (reason, outcome and outcome.message)
        assert APEX_WHEELS <= set(h.ground_truth()['wheel_contacts'])


def test_a_node_with_a_bad_start_pose_says_why_and_ends():
    params = {'~joints': {'bend_2': 0.3}}
    said = []
    with pytest.raises(SystemExit) as ended:
        robot_end.of_node(lambda name, default: params.get(name, default), said.append)
    assert ended.value.code == 1
    assert said == ["cannot start the simulated robot: start joint 'bend_2': not a joint of the robot; use "
                    'bend_i, bend_ii, bend_iii, bend_iv, camera_pan, camera_tilt, front_tilt, rear_tilt, rotation '
                    '(world straight_90, 90 mm, roll 1.57 rad)']


def test_a_node_with_a_world_that_is_not_there_says_why_and_ends():
    said = []
    with pytest.raises(SystemExit):
        robot_end.of_node(lambda name, default: {'~world': 'no_such_world'}.get(name, default), said.append)
    assert len(said) == 1 and 'no_such_world.yaml: cannot read' in said[0]
