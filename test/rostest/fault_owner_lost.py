#!/usr/bin/env python3
"""A goal whose owner is SIGKILLed mid-drive, over ROS.

The test clamps the robot, then starts ``goal_owner_client.py`` (node
``/goal_owner``, a process of its own) which sends a 2 m Drive; once the
robot moves the test kills that process with SIGKILL. The goal must end
(preempted or aborted) naming the owner, the odometry on /pirate/state must
stop changing, the safe hold be on the wire and an ERROR on /diagnostics
name the owner. The kill-to-end time and the travel after the kill are
printed (bench/faults measures them); every wait is on a condition with a
wall-clock deadline.
"""
import os
import signal
import subprocess
import sys
import time
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus, GoalStatusArray
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

from pirate import names
from pirate.msg import ControlArray, PirateAction, PirateActionResult, PirateGoal, RobotState, SetpointArray
from pirate.supervisory.goal_client_ros import SimpleGoalClient

from ready import wait_hold_on_wire, wait_robot_connected, wait_until

DEADLINE_S = 60.0
OWNER = '/goal_owner'
CLIENT = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'goal_owner_client.py')
#: Robot s over which the odometry must not change for the robot to stand (10 Mega cycles).
STILL_S = 1.0
STILL_MM = 1.0


class OwnerLostTest(unittest.TestCase):

    def setUp(self):
        rospy.init_node('owner_lost_test')
        self.states, self.statuses, self.results, self.diagnostics = [], [], [], []
        self.controls, self.setpoints = [], []
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self.states.append, queue_size=50)
        rospy.Subscriber(names.PIRATE_ACTION + '/status', GoalStatusArray, self.statuses.append, queue_size=50)
        rospy.Subscriber(names.PIRATE_ACTION + '/result', PirateActionResult, self.results.append, queue_size=50)
        rospy.Subscriber('/diagnostics', DiagnosticArray, self.diagnostics.append, queue_size=50)
        rospy.Subscriber(names.CONTROL_TOPIC, ControlArray, self.controls.append, queue_size=50)
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self.setpoints.append, queue_size=50)
        self.owner = None

    def tearDown(self):
        if self.owner is not None and self.owner.poll() is None:
            self.owner.kill()
            self.owner.wait(10.0)

    def test_a_drive_whose_owner_is_killed_ends_and_the_robot_stops(self):
        wait_robot_connected()
        client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(DEADLINE_S)))
        client.send_goal(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90))
        self.assertTrue(client.wait_for_result(rospy.Duration(DEADLINE_S)))
        self.assertEqual(client.get_state(), GoalStatus.SUCCEEDED, client.get_result().message)
        start_mm, known = self.states[-1].odometry, self._goal_ids()
        self.owner = subprocess.Popen([sys.executable, CLIENT])
        goal_id = wait_until(lambda: self._active_goal(known), 'the owner\'s Drive active', DEADLINE_S)
        wait_until(lambda: self.states[-1].odometry - start_mm > 50.0, 'the Drive moving', DEADLINE_S)
        killed_mm, killed_s, killed_robot_s = self.states[-1].odometry, time.monotonic(), rospy.get_time()
        os.kill(self.owner.pid, signal.SIGKILL)
        result = wait_until(lambda: self._result(goal_id), 'the Drive of the killed owner to end', DEADLINE_S)
        ended_s = time.monotonic()
        self.assertIn(result.status.status, (GoalStatus.PREEMPTED, GoalStatus.ABORTED), result.result.message)
        self.assertIn(OWNER, result.result.message)
        still = wait_until(self._standing, 'the odometry to stop changing', DEADLINE_S)
        self.assertLess(still.odometry - start_mm, 1000.0, 'the 2 m Drive ran on')
        self._assert_hold_on_wire()
        wait_until(self._owner_error, 'an ERROR on /diagnostics naming %s' % OWNER, DEADLINE_S)
        print('owner killed -> goal ended: %.3f s wall; travel after the kill %.1f mm; robot still by %.2f s '
              'robot after the kill' % (ended_s - killed_s, still.odometry - killed_mm,
                                        self._still_since(still) - killed_robot_s))

    def _goal_ids(self):
        return set(status.goal_id.id for array in list(self.statuses) for status in array.status_list)

    def _active_goal(self, known):
        """The id of an active goal not among ``known``, or None."""
        return next((status.goal_id.id for array in list(self.statuses) for status in array.status_list
                     if status.status == GoalStatus.ACTIVE and status.goal_id.id not in known), None)

    def _result(self, goal_id):
        return next((r for r in list(self.results) if r.status.goal_id.id == goal_id), None)

    def _standing(self):
        """The newest state when the odometry changed < STILL_MM over the last STILL_S robot s, else None."""
        states = list(self.states)
        newest = states[-1].header.stamp.to_sec()
        window = [s.odometry for s in states if s.header.stamp.to_sec() >= newest - STILL_S]
        span = states[0].header.stamp.to_sec() <= newest - STILL_S
        return states[-1] if span and max(window) - min(window) < STILL_MM else None

    def _still_since(self, still):
        """Robot s of the first state at the odometry the robot stands at."""
        return next(s.header.stamp.to_sec() for s in self.states if abs(s.odometry - still.odometry) < STILL_MM)

    def _assert_hold_on_wire(self):
        wait_hold_on_wire(self.controls, self.setpoints)

    def _owner_error(self):
        return any(s.level == DiagnosticStatus.ERROR and OWNER in s.message
                   for d in list(self.diagnostics) for s in d.status)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fault_owner_lost', OwnerLostTest)
