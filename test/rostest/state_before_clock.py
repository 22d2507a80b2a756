#!/usr/bin/env python3
"""pirate_state on simulated time: a Small State before the node's first
/clock is not taken (its arrival would read 0 and the robot look silent
from then on); states on a running clock are fresh. The test plays the
simulator. Waits on conditions, never on sleeps."""
import math
import threading
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock

from ready import wait_until
from pirate import names
from pirate.msg import RobotState, SmallState
from pirate.robot import tables, units
from pirate.srv import JointSensors

#: Simulated s of the first /clock, and Mega cycles run on it.
CLOCK_START_S, CYCLES = 1.0, 10


def cycle():
    """One refresh cycle of Small States, boards 20-28, the robot upright and still."""
    states = []
    for board in tables.BOARDS:
        data = [0] * 9
        if board == tables.IMU_BOARD:
            data[tables.SS_IMU_Y], data[tables.SS_IMU_Z] = (int(round(g)) for g in units.roll_to_gravity(math.pi / 2))
        states.append(SmallState(board=board, data=data))
    return states


class StateBeforeClock(unittest.TestCase):

    def setUp(self):
        rospy.init_node('state_before_clock')
        self.cond, self.states = threading.Condition(), []
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=100)
        self.clock = rospy.Publisher('/clock', Clock, queue_size=10)
        self.small = rospy.Publisher(names.SMALL_STATE_TOPIC, SmallState, queue_size=50)
        rospy.wait_for_service(names.JOINT_SENSORS_SERVICE, 30)
        self.sensors = rospy.ServiceProxy(names.JOINT_SENSORS_SERVICE, JointSensors)
        wait_until(lambda: self.small.get_num_connections() and self.clock.get_num_connections(),
                   'pirate_state to subscribe the Small States and /clock', 30)

    def _on_state(self, msg):
        with self.cond:
            self.states.append(msg)
            self.cond.notify_all()

    def test_a_small_state_before_the_clock_is_not_taken(self):
        for state in cycle():                       # no /clock yet: the node's time reads 0
            self.small.publish(state)
        self.assertEqual(self.sensors().age, float('inf'), 'a Small State was taken before the clock')
        for k in range(CYCLES):
            self.clock.publish(Clock(clock=rospy.Time.from_sec(CLOCK_START_S + 0.1 * k)))
            heard = len(self.states)
            for state in cycle():
                self.small.publish(state)
            with self.cond:
                self.assertTrue(self.cond.wait_for(lambda: len(self.states) > heard, 10.0),
                                'no robot state for cycle %d' % k)
        stale = ['%.2f s: boards %s' % (s.header.stamp.to_sec(), list(bytearray(s.silent_boards)))
                 for s in self.states if s.stale]
        self.assertEqual(stale, [], 'stale robot states')
        self.assertGreaterEqual(self.states[-1].header.stamp.to_sec(), CLOCK_START_S)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'state_before_clock', StateBeforeClock)
