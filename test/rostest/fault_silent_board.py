#!/usr/bin/env python3
"""A board goes silent mid-Clamp and mid-Drive, over ROS.

The test node is the relay between the simulated robot
(``/pirate/Small_State_raw``) and the state node (``/pirate/Small_State``);
it puts the Mega's word in place of every message of the board it
silences (the board + NO_ANSWER, data 0), as the Mega does with a board
that stops answering. Every wait is on a condition with a wall-clock
deadline.
"""
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from pirate import names
from pirate.msg import ControlArray, PirateAction, PirateGoal, RobotState, SetpointArray, SmallState
from pirate.robot import tables
from pirate.supervisory.goal_client_ros import SimpleGoalClient

from ready import wait_hold_on_wire, wait_robot_connected, wait_until

DEADLINE_S = 60.0


class SilentBoardTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('silent_board_relay')
        cls.silent = set()
        cls.feedback, cls.setpoints, cls.controls = [], [], []
        cls.relay = rospy.Publisher(names.SMALL_STATE_TOPIC, SmallState, queue_size=50)
        rospy.Subscriber(names.SMALL_STATE_TOPIC + '_raw', SmallState, cls._relay, queue_size=50)
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, cls.setpoints.append, queue_size=50)
        rospy.Subscriber(names.CONTROL_TOPIC, ControlArray, cls.controls.append, queue_size=50)
        cls.states = []
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, cls.states.append, queue_size=50)
        wait_robot_connected()
        cls.client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        assert cls.client.wait_for_server(rospy.Duration(DEADLINE_S))

    @classmethod
    def _relay(cls, msg):
        if msg.board in cls.silent:
            msg = SmallState(board=msg.board | tables.NO_ANSWER, data=[0] * tables.SMALL_STATE_SIZE)
        cls.relay.publish(msg)

    def _send(self, goal):
        self.feedback = []
        self.client.send_goal(goal, feedback_cb=self.feedback.append)

    def _silence_during(self, goal, primitive, board):
        """Silence ``board`` once ``primitive`` runs (its feedback, or for a drive the
        odometry moving: a goal's first feedback can be lost)."""
        start_mm = self.states[-1].odometry
        self._send(goal)
        wait_until(lambda: any(f.primitive == primitive for f in list(self.feedback))
                   or (primitive == 'drive' and abs(self.states[-1].odometry - start_mm) > 20.0), primitive)
        self.silent.add(board)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(DEADLINE_S)))
        result = self.client.get_result()
        self.assertEqual(self.client.get_state(), GoalStatus.ABORTED, result.message)
        self.assertIn('board %d silent' % board, result.message)
        self._assert_hold_on_wire()
        wait_until(lambda: self.states and self.states[-1].stale
                   and board in bytearray(self.states[-1].silent_boards), 'the state names board %d' % board)
        self._send(goal)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(DEADLINE_S)))
        self.assertEqual(self.client.get_state(), GoalStatus.REJECTED)
        self.assertIn('board %d silent' % board, self.client.get_result().message)
        self.silent.discard(board)
        wait_robot_connected()

    def _assert_hold_on_wire(self):
        wait_hold_on_wire(self.controls, self.setpoints)

    def test_silent_board_mid_clamp_then_mid_drive(self):
        self._silence_during(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90), 'clamp rear', 27)
        self._send(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(DEADLINE_S)))
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED, self.client.get_result().message)
        self._silence_during(PirateGoal(name=PirateGoal.DRIVE, pipe_diameter=90, distance=400.0, speed=100.0),
                             'drive', 22)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fault_silent_board', SilentBoardTest)
