#!/usr/bin/env python3
"""rostest: a cancel with no mission running (the panel's Stop) cancels a
mission goal stamped before it when that goal comes, and only such a goal."""
import threading
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalID, GoalStatus

from pirate import names
from pirate.msg import MissionActionGoal, MissionActionResult, MissionGoal
from pirate.srv import MissionCommand

import ready

DEADLINE_S = 60.0


class StopOvertakes(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('mission_stop_overtakes')
        cls.cond, cls.results = threading.Condition(), {}
        cls.goals = rospy.Publisher(names.MISSION_ACTION + '/goal', MissionActionGoal, queue_size=10)
        cls.ear = rospy.Subscriber(names.MISSION_ACTION + '/result', MissionActionResult, cls._on_result,
                                   queue_size=10)
        rospy.wait_for_service(names.MISSION_COMMAND_SERVICE, DEADLINE_S)
        cls.command = rospy.ServiceProxy(names.MISSION_COMMAND_SERVICE, MissionCommand)
        ready.wait_until(lambda: cls.goals.get_num_connections() and cls.ear.get_num_connections(),
                         'the executive to hear our goals and we its results', DEADLINE_S)

    @classmethod
    def _on_result(cls, msg):
        with cls.cond:
            cls.results[msg.status.goal_id.id] = msg
            cls.cond.notify_all()

    def send(self, goal_id, stamp):
        self.goals.publish(MissionActionGoal(goal_id=GoalID(id=goal_id, stamp=stamp),
                                             goal=MissionGoal(map='no_such_world', points=['a', 'b'])))
        with self.cond:
            self.assertTrue(self.cond.wait_for(lambda: goal_id in self.results, DEADLINE_S), goal_id)
            return self.results[goal_id]

    def test_a_cancel_between_missions_cancels_the_one_sent_before_only(self):
        sent_before = rospy.Time.now()
        said = self.command('cancel')
        self.assertTrue(said.ok and 'cancelled when it comes' in said.message, said.message)
        early = self.send('sent before the Stop', sent_before)
        self.assertEqual((early.status.status, early.result.status), (GoalStatus.RECALLED, 'cancelled'),
                         early.result.message)
        self.assertIn('cancelled by the operator before it started', early.result.message)
        late = self.send('sent after the Stop', rospy.Time.now())
        self.assertEqual((late.status.status, late.result.status), (GoalStatus.REJECTED, 'refused'))
        self.assertIn('no_such_world', late.result.message)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'mission_stop_overtakes', StopOvertakes)
