#!/usr/bin/env python3
"""A mission executive SIGKILLed mid-Drive, restarted, and resumed over ROS.

The test starts ``mission_executive`` as a process of its own (its log in
a fresh folder) and sends straight_90 pit -> target; once the Drive has
moved the robot it kills the process with SIGKILL. The manager ends the
dead owner's Drive (the robot stops short of the target); a second
executive under the same name, on the same log, answers ``last`` with the
interrupted mission, and ``resume`` takes it up: the mission's result on
/pirate/mission is succeeded, its Drive only for what was left, and the
odometry ends one planned Drive from where the Drive began. Every wait
is on a condition with a wall-clock deadline.
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

import rospkg
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from pirate import names
from pirate.msg import MissionAction, MissionActionFeedback, MissionActionResult, MissionGoal, RobotState
from pirate.srv import MissionCommand
from pirate.supervisory.goal_client_ros import SimpleGoalClient, wait_for_server

from ready import wait_robot_connected, wait_until

DEADLINE_S = 120.0
EXECUTIVE = os.path.join(rospkg.RosPack().get_path('pirate'), 'nodes', 'mission_executive')
ROUTE_MM = 500.0            # straight_90: pit at 400 mm, target at 900 mm
DRIVE_TOLERANCE_MM = 60.0   # the Drive's own stop, and the clamp's roll of the wheels


class ExecutiveKilledTest(unittest.TestCase):

    def setUp(self):
        rospy.init_node('executive_killed_test')
        self.states, self.feedback, self.results = [], [], []
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self.states.append, queue_size=50)
        rospy.Subscriber(names.MISSION_ACTION + '/feedback', MissionActionFeedback, self.feedback.append,
                         queue_size=50)
        rospy.Subscriber(names.MISSION_ACTION + '/result', MissionActionResult, self.results.append, queue_size=50)
        self.folder = tempfile.mkdtemp(prefix='mission_log')
        self.executive = None

    def tearDown(self):
        self._kill()
        shutil.rmtree(self.folder, ignore_errors=True)

    def test_a_mission_whose_executive_is_killed_is_resumed_by_a_new_one_and_ends_at_its_target(self):
        wait_robot_connected()
        self._start_executive()
        client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
        self.assertTrue(wait_for_server(client, DEADLINE_S))
        client.send_goal(MissionGoal(map='straight_90', points=['pit', 'target'], speed=30.0))
        wait_until(lambda: self._feedback_on('DRIVE'), 'the mission\'s Drive running', DEADLINE_S)
        drive_from_mm = self.states[-1].odometry
        wait_until(lambda: self.states[-1].odometry - drive_from_mm > 100.0, 'the Drive moving', DEADLINE_S)
        self._kill()
        stopped_mm = wait_until(self._standing_at, 'the robot to stop (the manager cancels the dead owner\'s goal)',
                                DEADLINE_S)
        self.assertLess(stopped_mm - drive_from_mm, ROUTE_MM - 100.0, 'the Drive ran on after its executive died')
        self._start_executive()
        command = rospy.ServiceProxy(names.MISSION_COMMAND_SERVICE, MissionCommand)
        command.wait_for_service(DEADLINE_S)
        self.assertIn('interrupted', command('last').message)
        answer = wait_until(lambda: self._resume(command), 'resume to be taken (the executive knows the odometry)',
                            DEADLINE_S)
        self.assertTrue(answer.ok, answer.message)
        self.assertIn('step 2 of 3 (DRIVE), run again from where the robot is', answer.message)
        # the killed executive's mission sent no result: the first one is the resumed mission's
        result = wait_until(lambda: self.results and self.results[0], 'the resumed mission\'s result',
                            2 * DEADLINE_S)
        self.assertEqual(result.status.status, GoalStatus.SUCCEEDED, result.result.message)
        self.assertLess(abs(self.states[-1].odometry - drive_from_mm - ROUTE_MM), DRIVE_TOLERANCE_MM,
                        (drive_from_mm, stopped_mm, self.states[-1].odometry))

    def _start_executive(self):
        self.executive = subprocess.Popen([sys.executable, EXECUTIVE, '__name:=mission_executive',
                                           '_log:=%s' % os.path.join(self.folder, 'mission_log.jsonl')])

    def _kill(self):
        if self.executive is not None and self.executive.poll() is None:
            os.kill(self.executive.pid, signal.SIGKILL)
            self.executive.wait(10.0)

    def _feedback_on(self, pab):
        return any(f.feedback.pab == pab and f.feedback.state == 'running' for f in list(self.feedback))

    def _standing_at(self):
        """The odometry when the last 20 states (2 s of robot time) agree within 1 mm, else None."""
        last = [s.odometry for s in list(self.states)[-20:]]
        return last[-1] if len(last) == 20 and max(last) - min(last) < 1.0 else None

    @staticmethod
    def _resume(command):
        """The answer to resume, or None while the new executive has no robot state yet."""
        answer = command('resume')
        return None if 'no robot state' in answer.message else answer


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fault_executive_killed', ExecutiveKilledTest)
