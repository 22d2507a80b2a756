#!/usr/bin/env python3
"""A route through a T-joint over ROS on the physics twin, paused during
Take T-joint and resumed (bad input: a pause during a junction).

The pause is asked (command service) as soon as the Pirate Server's
feedback says Take T-joint is looking for the T-joint; while paused, the
server runs no goal and the last setpoint array on the wire is the safe
hold. Resumed, the T-joint step runs again from where the robot is and the
mission ends at its target. Waits on feedback and results, never on sleeps."""
import threading
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus

from ready import wait_robot_connected
from seq_experiment import is_safe
from pirate import names
from pirate.msg import MissionAction, MissionGoal, PirateActionFeedback, SetpointArray
from pirate.srv import MissionCommand, ServerStatus
from pirate.supervisory.goal_client_ros import SimpleGoalClient

WAIT_S = 240.0
TAKING, LOOKING = 'Taking T-joint', 'looking for the junction'


class MissionTeeTest(unittest.TestCase):

    def setUp(self):
        rospy.init_node('mission_tee_test')
        wait_robot_connected()
        self.client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
        self.assertTrue(self.client.wait_for_server(rospy.Duration(60)))
        rospy.wait_for_service(names.MISSION_COMMAND_SERVICE, 60)
        self.command = rospy.ServiceProxy(names.MISSION_COMMAND_SERVICE, MissionCommand)
        self.status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
        self.cond, self.seen, self.setpoint = threading.Condition(), [], None
        self.looking = threading.Event()
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self._on_setpoint, queue_size=50)
        rospy.Subscriber(names.PIRATE_ACTION + '/feedback', PirateActionFeedback, self._on_pab, queue_size=50)

    def _on_setpoint(self, msg):
        with self.cond:
            self.setpoint = list(msg.data)
            self.cond.notify_all()

    def _on_pab(self, msg):
        if msg.feedback.server_state == TAKING and msg.feedback.pab_state == LOOKING:
            self.looking.set()

    def _on_mission(self, fb):
        with self.cond:
            self.seen.append(fb)
            self.cond.notify_all()

    def _wait_mission(self, predicate, what):
        with self.cond:
            self.assertTrue(self.cond.wait_for(lambda: any(predicate(f) for f in self.seen), WAIT_S),
                            '%s; seen %s' % (what, [(f.step, f.pab, f.waiting_for) for f in self.seen[-5:]]))

    def test_a_pause_during_the_t_joint_holds_the_robot_and_resume_takes_it(self):
        self.client.send_goal(MissionGoal(map='inspection_tee_90', points=['launch_pit', 'target']),
                              feedback_cb=self._on_mission)
        self.assertTrue(self.looking.wait(WAIT_S), 'Take T-joint never looked for the T-joint')
        self.assertTrue(self.command('pause').ok)
        self._wait_mission(lambda f: f.waiting_for.startswith('resume'), 'the mission waits for resume')
        self.assertFalse(self.status().active)                     # the T-joint goal was cancelled
        with self.cond:
            self.assertTrue(self.cond.wait_for(lambda: self.setpoint is not None and is_safe(self.setpoint),
                                               WAIT_S), self.setpoint)   # the safe hold is on the wire
        self.assertTrue(self.command('resume').ok)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(WAIT_S)))
        result = self.client.get_result()
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED, '\n'.join(result.log))
        tee_steps = [line for line in result.log if line.startswith('step 3/5: T_JOINT')]
        self.assertEqual(len(tee_steps), 2, result.log)              # the T-joint step, and run again
        self.assertTrue(any('tee_1 found where the map has it' in line for line in result.log), result.log)
        self.assertTrue(any(line.startswith('step 5/5: HOME') for line in result.log), result.log)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'mission_tee_pause', MissionTeeTest)
