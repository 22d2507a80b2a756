"""The rotation-at-limit livelock, on a kinematic robot.

The start: rear nominal but not straight, the rotation at its +0.7 rad
limit, front lifted. On main Clamp Straight looped unclamp rear -> rotate
rear (eq 5.2's target clipped to 0.7: no motion) -> clamp rear until the
60-state cap, and Home left the rotation where it was, so Home + Clamp
Straight looped the same way. The robot here is the report's kinematics
only (Table 4.5: the rotation turns the part that is not clamped; theta =
rear roll - front roll), so the test shows the table's logic, not physics.
"""
import math

import pytest

from pirate.sequencer.pabs.clamp import Clamp
from pirate.sequencer.pabs.home import Home

from kinematic_robot import BOOK, KinematicRobot, run

GUARDS = BOOK.for_diameter(90)

def assert_clamped_straight(robot):
    straight = GUARDS.region('straight')
    assert straight[0] <= robot.rear <= straight[1]
    assert abs(robot.rotation) <= GUARDS.align_tolerance
    assert robot.clamped == {'front': True, 'rear': True}


@pytest.mark.parametrize('rear_roll, rotation', [(1.45, 0.7), (1.69, -0.7)])
def test_clamp_straight_from_the_rotation_limit(rear_roll, rotation):
    robot = KinematicRobot(rear_roll, rotation, front_tilt=0.4)
    run(Clamp(), robot)
    assert_clamped_straight(robot)
    clipped = robot.executed.index('rotate rear')
    assert robot.executed[clipped + 1:clipped + 4] == ['clamp rear', 'unclamp front partial', 'rotate front']


def test_home_aligns_then_clamp_straight_converges():
    robot = KinematicRobot(1.45, 0.7, front_tilt=0.4)
    robot.clamp('rear')
    robot.clamp('front')
    robot.executed = []
    run(Home(), robot)
    assert robot.executed == ['unclamp front', 'align', 'unclamp rear', 'move front down']
    assert robot.rotation == 0.0 and robot.clamped == {'front': False, 'rear': False}
    robot.executed = []
    run(Clamp(), robot)
    assert_clamped_straight(robot)
    assert len(robot.executed) < 12


def test_home_of_an_aligned_robot_is_the_reports():
    robot = KinematicRobot(math.pi / 2, 0.0, front_tilt=0.4)
    robot.clamp('rear')
    robot.clamp('front')
    robot.executed = []
    run(Home(), robot)
    assert robot.executed == ['unclamp front', 'unclamp rear', 'move front down']
