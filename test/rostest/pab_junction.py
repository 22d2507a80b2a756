#!/usr/bin/env python3
"""rostest: Take T-joint and Take mitre bend over ROS with a real action
client, against the physics twin (sim time).

The goals come from the .test file (defaults: the T-joint case). A goal
the PAB does not take (``~refused``, MITRE_BEND DOWN) is rejected at once
with its reason. ``~clamp`` (Clamp Straight; Clamp Sideways toward a
turn), then ``~junction`` through the first junction: SUCCEEDED with the
primitives ``~expected``, the result's junction_odometry within
``~junction_odometry`` (and junction_missing false), ``~server_state`` in
feedback, Idle Clamped after and the roll within 0.05 rad of ``~target``.
The same goal again, toward the second junction, is cancelled at a random
instant of sim time within ``~cancel_within`` (about its duration; seed
printed): PREEMPTED with the safe hold on the wire (or SUCCEEDED when the
draw came after it ended); then, with ``~home_after_cancel``, Home leaves
the robot Idle Unclamped from wherever the cancel left it (refused half
round a corner: the turn re-sent first, as the refusal says); with
``~resend_after_cancel`` (a turn), the same goal re-sent finishes the turn
from where the robot is: SUCCEEDED, Idle Clamped at ``~target`` (refused
asking for ``~clamp`` first when cancelled as the rear clamped past the
corner: then that clamp ends it). Cancelled while driving into the new
pipe or straightening after it, the re-sent turn drives what is left and
re-adjusts (the server's record of the turn; nothing sensed tells it from
a robot before a bend). Not re-sent when the draw came after the goal
ended. Built on seq_experiment's helpers.
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
MITRE_BEND_DOWN = {'name': PirateGoal.MITRE_BEND, 'option': PirateGoal.DOWN}
#: What Home's refusal half round a corner asks for (pirate.sequencer.pabs.home).
RESEND_TURN = 're-send the turn toward the'
#: The last steps of a turn (pirate.sequencer.pabs.junction): re-sent, it says it resumed the drive in.
PAST_THE_CORNER = ('driving into the new pipe', 'straightening')
#: Where pirate_manager keeps how the last goal ended (manager_node.ENDED_PARAM).
LAST_GOAL_ENDED = '/pirate_manager/last_goal_ended'


class PabJunctionTest(SequencerTest):
    """Clamp, take a junction, cancel the next at random, Home."""

    def _assert_refused(self, spec):
        """A direction not taken yet: refused at once with the reason, no junction in the result."""
        self._send(spec)
        state, result, text = self._finish()
        self.assertEqual(state, GoalStatus.REJECTED, text)
        self.assertIn('not yet taken by this PAB', text)
        self.assertTrue(math.isnan(result.junction_odometry) and not result.junction_missing)

    def test_scenario(self):
        junction = rospy.get_param('~junction', T_JOINT)
        self._assert_refused(rospy.get_param('~refused', MITRE_BEND_DOWN))
        self._run(rospy.get_param('~clamp', CLAMP))
        result = self._run(junction)
        self._assert_sequence(self._assert_trace(result), rospy.get_param('~expected'))
        self.assertIn(rospy.get_param('~server_state', 'Taking T-joint'), self.server_states)
        low, high = rospy.get_param('~junction_odometry', [250.0, 500.0])
        self.assertTrue(low < result.junction_odometry < high, result.junction_odometry)
        self.assertFalse(result.junction_missing)
        self.assertEqual(result.server_state, 'Idle Clamped')
        target = float(rospy.get_param('~target', math.pi / 2))
        self.assertLessEqual(abs(math.remainder(self.state.orientation - target, 2 * math.pi)), 0.05,
                             self.state.orientation)
        seed = self._cancel_at_random(junction, 'pab_junction: %s' % junction)
        if rospy.get_param('~resend_after_cancel', False):
            self._resend(junction, rospy.get_param('~clamp', CLAMP), target, seed)
        if rospy.get_param('~home_after_cancel', True):
            self._home(junction, seed)

    def _home(self, junction, seed):
        """Home from wherever the cancel left the robot: Idle Unclamped. Half
        round a corner Home is refused saying to re-send the turn first; then
        the turn re-sent finishes, and Home after it."""
        self._assert_kept_how_the_turn_ended(seed)
        self._send(HOME)
        state, result, why = self._finish()
        if state == GoalStatus.REJECTED and RESEND_TURN in why:
            rospy.loginfo('pab_junction: Home refused (%s); the turn re-sent first', why)
            self._run(junction)
            result = self._run(HOME)
        else:
            self.assertEqual(state, GoalStatus.SUCCEEDED, 'seed %d: %s; Home: %s' % (seed, self.cancelled_text, why))
        self.assertEqual(result.server_state, 'Idle Unclamped', 'seed %d: %s' % (seed, self.cancelled_text))

    def _assert_kept_how_the_turn_ended(self, seed):
        """The manager keeps how the cancelled turn ended in a parameter a
        manager started again takes back (Home there still refused)."""
        kept = rospy.get_param(LAST_GOAL_ENDED)
        said = 'seed %d: %s; kept %s' % (seed, self.cancelled_text, kept)
        self.assertEqual(kept['pab'], rospy.get_param('~server_state', 'Taking T-joint'), said)
        if 'cancelled during' in self.cancelled_text:
            self.assertEqual(kept['status'], 'preempted', said)
            self.assertTrue(self.cancelled_text.endswith('cancelled during %s' % kept['state']), said)
        self.assertLessEqual(abs(kept['odometry_mm'] - self.state.odometry), 20.0, said)

    def _resend(self, junction, clamp, target, seed):
        """The cancelled turn re-sent finishes it (or the clamp it asks for first does)."""
        text = self.cancelled_text
        if 'cancelled during' not in text:
            rospy.loginfo('pab_junction: not re-sent, the turn had ended (%s)', text)
            return
        self._send(junction)
        state, result, why = self._finish()
        if state == GoalStatus.REJECTED and 'Clamp Sideways' in why:
            result = self._run(clamp)
        else:
            self.assertEqual(state, GoalStatus.SUCCEEDED, 'seed %d: %s; re-sent: %s' % (seed, text, why))
            if any(step in text for step in PAST_THE_CORNER):
                self.assertIn('resumed past the corner', result.message, 'seed %d' % seed)
        rospy.loginfo('pab_junction: %s, re-sent: %s', text, result.message)
        self.assertEqual(result.server_state, 'Idle Clamped', 'seed %d: %s' % (seed, text))
        self.assertLessEqual(abs(math.remainder(self.state.orientation - target, 2 * math.pi)), 0.05,
                             'seed %d: roll %.3f' % (seed, self.state.orientation))


if __name__ == '__main__':
    rostest.rosrun('pirate', 'pab_junction', PabJunctionTest)
