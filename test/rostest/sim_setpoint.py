#!/usr/bin/env python3
"""rostest: setpoints reach the simulated joints; bad input is dropped.

Runs against launch/robot.launch (sim_robot + pirate_state) in simulated
time. Every wait is on a condition with a wall-clock deadline, never a sleep.
"""
import math
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log

from pirate import names
from pirate.robot import commands, tables, units
from pirate.msg import ControlArray, LimitArray, SetpointArray, SmallState
from pirate.srv import JointSensors

DEADLINE_S = 60.0        # wall seconds for any one condition
POLL_S = 0.02            # how often a condition is re-checked (wall)


def wait_until(condition, what, deadline=DEADLINE_S):
    """Return the first truthy value of ``condition()``; fail after ``deadline``."""
    end = time.monotonic() + deadline
    while time.monotonic() < end and not rospy.is_shutdown():
        value = condition()
        if value:
            return value
        time.sleep(POLL_S)
    raise AssertionError('timed out after %.0f s waiting for %s' % (deadline, what))


class SimSetpointTest(unittest.TestCase):
    """Drives the simulated robot through the three command arrays."""

    @classmethod
    def setUpClass(cls):
        rospy.init_node('sim_setpoint_test')
        cls.logs = []
        rospy.Subscriber('/rosout', Log, cls.logs.append, queue_size=100)
        pubs = {name: rospy.Publisher(topic, kind, queue_size=10, latch=True)
                for name, topic, kind in (('setpoint', names.SETPOINT_TOPIC, SetpointArray),
                                          ('control', names.CONTROL_TOPIC, ControlArray),
                                          ('limit', names.LIMITS_TOPIC, LimitArray))}
        cls.bad_state = rospy.Publisher(names.SMALL_STATE_TOPIC, SmallState, queue_size=10)
        for pub in list(pubs.values()) + [cls.bad_state]:
            wait_until(lambda p=pub: p.get_num_connections() > 0, 'subscriber of %s' % pub.name)
        cls.raw_setpoint = pubs['setpoint']
        cls.control = commands.Control(pubs['control'], lambda d: ControlArray(data=d))
        cls.setpoint = commands.Setpoint(pubs['setpoint'], lambda d: SetpointArray(data=d),
                                         cls.control)
        # The robot's Mega stops every board without a setpoint array for
        # 0.25 s (its watchdog): stream the newest array at 10 Hz, as the manager does.
        cls.stream = [None]
        rospy.Timer(rospy.Duration(0.1), lambda _e: cls.stream[0] and pubs['setpoint'].publish(
            SetpointArray(data=cls.stream[0])))
        rospy.wait_for_service(names.JOINT_SENSORS_SERVICE, timeout=DEADLINE_S)
        cls.joint_sensors = rospy.ServiceProxy(names.JOINT_SENSORS_SERVICE, JointSensors)

    def angle(self, name):
        reply = self.joint_sensors()
        self.assertFalse(reply.stale, 'state is stale (age %.2f s)' % reply.age)
        return reply.position[reply.name.index(name)]

    def test_1_setpoint_moves_the_joint_and_service_reports_rad(self):
        wait_until(lambda: not self.joint_sensors().stale, 'fresh state')
        self.assertAlmostEqual(self.angle('front_tilt'), 0.0, places=2)
        self.control.set_mode('front_tilt', 'position')
        self.control.command('play')
        self.setpoint.set('front_tilt', units.rad_to_encoder(0.5))
        self.setpoint.publish_now()
        self.stream[0] = self.setpoint.get_all()
        reached = wait_until(lambda: abs(self.angle('front_tilt') - 0.5) < 0.01,
                             'front_tilt at 0.5 rad')
        self.assertTrue(reached)
        reply = self.joint_sensors()
        self.assertEqual(list(reply.name), list(tables.JOINT_NAMES))
        self.assertLess(reply.age, 1.0)

    def test_2_out_of_range_setpoint_is_clamped_not_obeyed(self):
        self.control.set_mode('rotation', 'position')
        self.control.command('play')
        data = self.setpoint.get_all()
        data[tables.element('rotation').index] = 32000        # ~15 rad: beyond +-0.7
        self.raw_setpoint.publish(SetpointArray(data=data))
        self.stream[0] = data
        wait_until(lambda: self.angle('rotation') > 0.65, 'rotation towards its 0.7 rad limit')
        wait_until(lambda: abs(self.angle('rotation') - 0.7) < 0.005, 'rotation at 0.7 rad')
        self.assertLess(self.angle('rotation'), 0.7 + 0.005)
        wait_until(lambda: self._logged('sim_robot', 'rotation: setpoint 32000'),
                   'sim_robot logs the clamp')

    def test_3_bad_small_state_dropped_and_service_answers(self):
        for _ in range(5):
            self.bad_state.publish(SmallState(board=99, data=[0] * 9))
        self.bad_state.publish(SmallState(board=22, data=[0, 0, 0, 3000, 0, 0, 0, 0, 0]))
        wait_until(lambda: self._logged('pirate_state', 'beyond an AS5055'), 'angle refusal logged')
        self.assertEqual(self._logged('pirate_state', 'unknown board 99'), 1,
                         'an unknown board is logged exactly once')
        reply = self.joint_sensors()
        self.assertFalse(reply.stale)
        self.assertTrue(all(abs(p) <= math.pi for p in reply.position))
        wait_until(lambda: abs(self.angle('front_tilt') - 0.5) < 0.01, 'state still served')

    def _logged(self, node, text):
        return sum(1 for log in list(self.logs) if log.name.endswith(node) and text in log.msg)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'sim_setpoint', SimSetpointTest)
