#!/usr/bin/env python3
"""rostest: a clamp PAB (Clamp Straight / Clamp Sideways) over ROS with a
real action client, against the physics twin (sim time).

1. The goal ``~goal``, during which the simulator is stopped for 1 s of
   wall time (a loaded laptop; the robot is late, not silent), succeeds
   with the primitives ``~expected``, its
   ``~loops`` passes each run ``~min_passes``..``~max_passes`` times (Table
   6.2's pass, which a clamp on a side needs when it rolls the robot out of
   the straight band; seq_experiment's check), and leaves
   the rear in the straight region of Table 5.4 moved to ``~target`` (rad),
   the server Idle Clamped.
2. A Drive is cancelled at a random instant of its run: PREEMPTED with the
   safe hold on the wire, the robot still clamped.
3. Home is cancelled at a random instant, then sent again: Idle Unclamped.
4. ``~goal`` from there is cancelled at a random instant, then sent again:
   it must end Idle Clamped at the target whatever the cancel left (a part
   clamped, partly clamped, half rotated).
Each random instant is drawn within ``~cancel_within`` sim s, seed printed.
Built on seq_experiment's helpers.
"""
import math

import rospy
import rostest

from actionlib_msgs.msg import GoalStatus
from pirate.msg import PirateGoal

from seq_experiment import SequencerTest

HOME = {'name': PirateGoal.HOME}
DRIVE = {'name': PirateGoal.DRIVE, 'distance': 200.0, 'speed': 25.0}
DRIVE_S = 8.0              # sim s the Drive takes: 200 mm at 25 mm/s
STRAIGHT_BAND = (1.52 - math.pi / 2, 1.62 - math.pi / 2)   # Table 5.4 around the target


class PabClampTest(SequencerTest):
    """Clamp, Drive cancelled, Home cancelled and again, clamp cancelled and again."""

    def _assert_clamped_at_target(self, result, tag):
        self.assertEqual(result.server_state, 'Idle Clamped', tag)
        offset = math.remainder(self.state.orientation - float(rospy.get_param('~target')), 2 * math.pi)
        self.assertTrue(STRAIGHT_BAND[0] <= offset <= STRAIGHT_BAND[1],
                        '%s: roll %.3f rad' % (tag, self.state.orientation))

    def test_scenario(self):
        spec = rospy.get_param('~goal')
        self._send(spec)
        self._wait_sim(2.0)
        self._stall_simulator(1.0)
        state, result, text = self._finish()
        self.assertEqual(state, GoalStatus.SUCCEEDED, 'after a stalled simulator: %s' % text)
        self._assert_sequence(self._assert_trace(result), rospy.get_param('~expected'))
        self._assert_clamped_at_target(result, 'first clamp')
        seed = self._cancel_at_random(DRIVE, 'pab_clamp: Drive', within_s=DRIVE_S)
        self.assertEqual(self.client.get_result().server_state, 'Idle Clamped', 'seed %d' % seed)
        seed = self._cancel_at_random(HOME, 'pab_clamp: Home')
        self.assertEqual(self._run(HOME).server_state, 'Idle Unclamped', 'seed %d' % seed)
        seed = self._cancel_at_random(spec, 'pab_clamp: %s' % spec)
        self._assert_clamped_at_target(self._run(spec), 'clamp after the cancel, seed %d' % seed)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'pab_clamp', PabClampTest)
