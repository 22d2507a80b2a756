#!/usr/bin/env python3
"""rostest: Take T-joint over ROS with a real action client, against the
physics twin (sim time), issue 10.5.

MITRE_BEND DOWN is rejected at once with its reason (no turn is taken
yet). Clamp Straight, then T_JOINT STRAIGHT through the first of two T-joints:
SUCCEEDED with the primitives ``~expected``, the result's junction_odometry
where the T-joint is (and junction_missing false), the server "Taking
T-joint" in feedback and Idle Clamped after. T_JOINT STRAIGHT again, toward
the second, is cancelled at a random instant of sim time within
``~cancel_within`` (about its duration; seed printed): PREEMPTED with the
safe hold on the wire (or SUCCEEDED when the draw came after it ended);
then Home leaves the robot Idle Unclamped from wherever the cancel left it.
Built on seq_experiment's helpers.
"""
import math

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from pirate.msg import PirateGoal

from seq_experiment import SequencerTest

CLAMP = {'name': PirateGoal.CLAMP_STRAIGHT}
T_JOINT = {'name': PirateGoal.T_JOINT, 'option': PirateGoal.STRAIGHT}
HOME = {'name': PirateGoal.HOME}
MITRE_BEND = {'name': PirateGoal.MITRE_BEND, 'option': PirateGoal.DOWN}


class PabJunctionTest(SequencerTest):
    """Clamp, cross a T-joint, cancel the next at random, Home."""

    def _assert_mitre_bend_refused(self):
        """MITRE_BEND takes no direction yet: refused at once with the reason, no junction in the result."""
        self._send(MITRE_BEND)
        state, result, text = self._finish()
        self.assertEqual(state, GoalStatus.REJECTED, text)
        self.assertIn('not yet taken by this PAB', text)
        self.assertTrue(math.isnan(result.junction_odometry) and not result.junction_missing)

    def test_scenario(self):
        self._assert_mitre_bend_refused()
        self._run(CLAMP)
        result = self._run(T_JOINT)
        self.assertEqual(self._assert_trace(result), rospy.get_param('~expected'))
        self.assertIn('Taking T-joint', self.server_states)
        self.assertTrue(250.0 < result.junction_odometry < 500.0, result.junction_odometry)
        self.assertFalse(result.junction_missing)
        self.assertEqual(result.server_state, 'Idle Clamped')
        self._assert_straight()
        seed = self._cancel_at_random(T_JOINT, 'pab_junction: T_JOINT')
        self.assertEqual(self._run(HOME).server_state, 'Idle Unclamped', 'seed %d' % seed)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'pab_junction', PabJunctionTest)
