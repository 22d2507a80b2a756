#!/usr/bin/env python3
"""A second writer on the command topics, over ROS.

The test node itself is the rogue: it publishes setpoint arrays at 50 Hz
(what opened the clamped front in the issue). Every wait is on a condition
with a wall-clock deadline.
"""
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

from pirate import names
from pirate.msg import ControlArray, PirateAction, PirateGoal, SetpointArray
from pirate.robot import tables
from pirate.supervisory.goal_client_ros import SimpleGoalClient

from ready import wait_robot_connected, wait_until

DEADLINE_S = 30.0
STOP = 8


class RogueWriterTest(unittest.TestCase):

    def test_a_second_setpoint_writer_is_detected_and_the_robot_held(self):
        rospy.init_node('rogue_writer')
        diagnostics, controls = [], []
        rospy.Subscriber('/diagnostics', DiagnosticArray, diagnostics.append, queue_size=50)
        rospy.Subscriber(names.CONTROL_TOPIC, ControlArray, controls.append, queue_size=50)
        wait_robot_connected()
        client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(DEADLINE_S)))
        rogue = rospy.Publisher(names.SETPOINT_TOPIC, SetpointArray, queue_size=1)
        wait_until(lambda: rogue.get_num_connections() >= 2, 'the sim and the manager subscribed', DEADLINE_S)
        stop = threading.Event()

        def flood():
            data = [0] * tables.SETPOINT_SIZE
            data[tables.element('bend_i').index] = 200
            while not stop.is_set():
                rogue.publish(SetpointArray(data=data))
                stop.wait(0.02)
        threading.Thread(target=flood, daemon=True).start()
        try:
            wait_until(lambda: self._rogue_error(diagnostics), 'an ERROR on /diagnostics naming the rogue')
            wait_until(lambda: controls and controls[-1].data[tables.element('rear_module').index] == STOP,
                       'STOP on the control array')
            client.send_goal(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90))
            self.assertTrue(client.wait_for_result(rospy.Duration(DEADLINE_S)))
            result = client.get_result()
            self.assertFalse(result.success)
            self.assertIn(rospy.get_name(), result.message)
        finally:
            stop.set()

    @staticmethod
    def _rogue_error(diagnostics):
        return any(s.level == DiagnosticStatus.ERROR and rospy.get_name() in s.message
                   for d in list(diagnostics) for s in d.status)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fault_rogue_writer', RogueWriterTest)
