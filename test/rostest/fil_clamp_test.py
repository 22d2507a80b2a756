#!/usr/bin/env python3
"""Clamp Straight through the firmware-in-the-loop chain.

1. The simple clamp straight (upright start, 90 mm) succeeds end to end
   through serial_node <-> pty <-> native firmware <-> simulated boards.
2. Unplug mid-PAB: the PAB aborts (the state stops flowing), the firmware
   stops every motor on its own; after replugging (the Mega resets) the
   link comes back and the next goal succeeds.
3. Reset mid-PAB (the Mega restarts with the cable in, too fast for the
   state to go stale): the goal ends, saying so, and nothing is re-armed:
   every setpoint array on the wire holds the wheels and the bends at 0
   and the robot does not travel.
"""
import time
import unittest

import actionlib
import rospy
import rostest

import ready
from std_msgs.msg import String

from pirate import names
from pirate.msg import PirateAction, PirateGoal, RobotState, SetpointArray
from pirate.robot import link_watch, tables
from pirate.supervisory.goal_client_ros import SimpleGoalClient

FAULT_TOPIC = '/fil_robot/fault'
#: The setpoint elements the safe hold puts at 0 (pirate.robot.hold).
HELD = [tables.element(name).index for name in ('front_tilt', 'bend_i', 'bend_ii', 'bend_iii', 'bend_iv', 'wheels')]


class FilClampTest(unittest.TestCase):

    def setUp(self):
        self.client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        self.assertTrue(self.client.wait_for_server(rospy.Duration(60)), 'no Pirate Server')
        self.fault = rospy.Publisher(FAULT_TOPIC, String, queue_size=5)
        self.states, self.odometry, self.wire = [], [], []
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState,
                         lambda m: self.states.append((time.monotonic(), m.stale)), queue_size=50)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, lambda m: self.odometry.append(m.odometry),
                         queue_size=50)
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, lambda m: self.wire.append(list(m.data)),
                         queue_size=50)
        deadline = time.monotonic() + 60
        while not any(not stale for _, stale in self.states[-5:]):
            self.assertLess(time.monotonic(), deadline, 'no fresh robot state through FIL')
            time.sleep(0.1)
        deadline = time.monotonic() + 10
        while self.fault.get_num_connections() == 0:
            self.assertLess(time.monotonic(), deadline, 'fil_robot not listening for faults')
            time.sleep(0.1)
        ready.wait_robot_connected(60)

    def _clamp(self, feedback=None):
        self.client.send_goal(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90),
                              feedback_cb=feedback)

    def test_1_clamp_straight_succeeds_through_fil(self):
        self._clamp()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(120)), 'no result')
        result = self.client.get_result()
        self.assertTrue(result.success, result.message)

    def _fault_mid_clamp(self, fault):
        """Home, start a Clamp Straight, and inject ``fault`` (a fault topic word) a second into it."""
        self.client.send_goal(PirateGoal(name=PirateGoal.HOME, pipe_diameter=90))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(120)), 'home: no result')
        primitives = []
        self._clamp(lambda fb: primitives.append(fb.primitive))
        deadline = time.monotonic() + 30
        while not primitives:
            self.assertLess(time.monotonic(), deadline, 'PAB never started')
            time.sleep(0.05)
        time.sleep(1.0)   # mid-PAB
        self.fault.publish(String(fault))

    def test_2_unplug_mid_pab_aborts_then_next_goal_succeeds(self):
        self._fault_mid_clamp('unplug')
        self.assertTrue(self.client.wait_for_result(rospy.Duration(30)), 'no result after unplug')
        self.assertFalse(self.client.get_result().success, 'PAB did not abort on unplug')
        self.assertEqual(self.client.get_state(), actionlib.GoalStatus.ABORTED)
        time.sleep(0.5)
        self.fault.publish(String('replug'))
        replugged = time.monotonic()
        deadline = replugged + 30
        while not any(t > replugged and not stale for t, stale in self.states):
            self.assertLess(time.monotonic(), deadline, 'link did not come back')
            time.sleep(0.1)
        self._clamp()
        self.assertTrue(self.client.wait_for_result(rospy.Duration(120)), 'no result')
        result = self.client.get_result()
        self.assertTrue(result.success, result.message)

    def test_3_reset_mid_pab_ends_the_goal_and_rearms_nothing(self):
        self._fault_mid_clamp('reset')
        self.assertTrue(self.client.wait_for_result(rospy.Duration(30)), 'no result after the reset')
        result = self.client.get_result()
        self.assertFalse(result.success, 'the PAB went on through a reset')
        self.assertIn(link_watch.BACK_REASON, result.message)
        sent, odometry = len(self.wire), self.odometry[-1]
        time.sleep(3.0)
        after = self.wire[sent:]
        self.assertTrue(after, 'no setpoint array on the wire for 3 s')
        moving = [s for s in after if any(s[i] for i in HELD)]
        self.assertFalse(moving, '%d of %d setpoint arrays after the reset move a joint: %s'
                         % (len(moving), len(after), moving[:1]))
        self.assertLess(abs(self.odometry[-1] - odometry), 10.0, 'the robot travelled after the reset')


if __name__ == '__main__':
    rospy.init_node('fil_clamp_test')
    rostest.rosrun('pirate', 'fil_clamp_straight', FilClampTest)
