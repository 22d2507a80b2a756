"""Issue 10.1, the rotation-at-limit livelock, on a kinematic robot.

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

from pirate.robot import safety
from pirate.state.feed import RobotView
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs.clamp import Clamp
from pirate.sequencer.pabs.home import Home
from pirate.sequencer.primitives import Refused, clamp_name
from pirate.sequencer.server import PabContext

GUARDS = GuardBook(*load_files()).for_diameter(90)
PRESS_MNM = 241.0       # the outer spring on the wall (twin, clamp torque 256)


class KinematicRobot(object):
    """Feed and primitives of a robot that only rolls and rotates."""

    def __init__(self, rear_roll, rotation, front_tilt):
        self.rear, self.rotation = rear_roll, rotation
        self.front = rear_roll - rotation
        self.angles = {j: 0.0 for j in ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')}
        self.angles.update(rotation=rotation, front_tilt=front_tilt)
        self.efforts = {}
        self.clamped = {'front': False, 'rear': False}
        self.executed = []

    # --- feed ---
    def latest(self):
        return RobotView(dict(self.angles), self.rear, 0.0, 0.0, 1.0, dict(self.efforts))

    def check(self):
        """Never cancelled, never stale."""

    # --- primitives ---
    def change_control_mode(self, joint, mode):
        """Modes do not matter to kinematics."""

    def move_front(self, kind='move_front'):
        self.executed.append(kind.replace('_', ' '))
        self.angles['front_tilt'] = GUARDS.move(kind).guard

    def clamp(self, part, kind='clamp'):
        self.executed.append(clamp_name(kind, part))
        pair = GUARDS.pair(kind, part)
        self.angles.update({pair.outer.joint: pair.outer.guard - 0.01, pair.inner.joint: pair.inner.guard + 0.01})
        self.efforts[pair.outer.joint] = PRESS_MNM
        self.clamped[part] = True

    def unclamp(self, part, partial=False):
        self.executed.append('unclamp %s%s' % (part, ' partial' if partial else ''))
        pair = GUARDS.pair('unclamp_partial' if partial else 'unclamp', part)
        self.angles.update({pair.outer.joint: pair.outer.guard + 0.01, pair.inner.joint: pair.inner.guard - 0.01})
        self.efforts[pair.outer.joint] = 0.0
        self.clamped[part] = False

    def rotate(self, target_rad, name='rotate'):
        if not safety.rotation_ok(target_rad):
            raise Refused('rotation %.3f beyond the limit' % target_rad)
        assert not all(self.clamped.values()), 'rotating against two clamped parts'
        self.executed.append(name)
        self.rotation = self.angles['rotation'] = target_rad
        if self.clamped['front']:
            self.rear = self.front + target_rad
        else:
            self.front = self.rear - target_rad     # rear clamped, or the lighter front

    def align(self):
        self.rotate(0.0, name='align')


def run(pab, robot):
    ctx = PabContext(robot, robot, GUARDS, None, lambda *state: None)
    return pab.run(ctx)


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
