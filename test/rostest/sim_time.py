#!/usr/bin/env python3
"""rostest: the simulated robot runs faster than wall time when asked.

Measures simulated seconds (/clock) against wall seconds over a window and
checks the property "faster than wall time, not faster than asked" (ratio
between ~rate/2 and ~rate * 1.25), not a timing figure: the lower bound
leaves room for a loaded machine. Meanwhile the state must stay fresh.
"""
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock

from pirate import names
from pirate.srv import JointSensors

DEADLINE_S = 60.0       # wall seconds for the stack to come up
WINDOW_S = 3.0          # wall seconds of measurement
POLL_S = 0.05


class SimTimeTest(unittest.TestCase):
    """Compares /clock with the wall clock."""

    @classmethod
    def setUpClass(cls):
        rospy.init_node('sim_time_test')
        cls.rate = float(rospy.get_param('~rate'))
        cls.lock = threading.Lock()
        cls.samples = []          # (wall monotonic s, sim s)
        rospy.Subscriber('/clock', Clock, cls._on_clock, queue_size=100)
        rospy.wait_for_service(names.JOINT_SENSORS_SERVICE, timeout=DEADLINE_S)
        cls.joint_sensors = rospy.ServiceProxy(names.JOINT_SENSORS_SERVICE, JointSensors)

    @classmethod
    def _on_clock(cls, msg):
        with cls.lock:
            cls.samples.append((time.monotonic(), msg.clock.to_sec()))

    def _latest(self):
        with self.lock:
            return self.samples[-1] if self.samples else None

    def _wait(self, condition, what, deadline):
        end = time.monotonic() + deadline
        while not condition():
            self.assertLess(time.monotonic(), end, 'timed out waiting for %s' % what)
            time.sleep(POLL_S)

    def test_sim_time_runs_faster_than_wall_time(self):
        self._wait(lambda: self._latest() is not None, '/clock', DEADLINE_S)
        wall0, sim0 = self._latest()
        stale_seen = []
        # The window is a measurement interval; the service is polled through it.
        while time.monotonic() - wall0 < WINDOW_S:
            reply = self.joint_sensors()
            stale_seen.append(reply.stale)
            time.sleep(POLL_S)
        wall1, sim1 = self._latest()
        ratio = (sim1 - sim0) / (wall1 - wall0)
        rospy.loginfo('sim_time: %.2f sim s in %.2f wall s: x%.2f (asked x%.1f)',
                      sim1 - sim0, wall1 - wall0, ratio, self.rate)
        self.assertGreater(ratio, max(self.rate / 2.0, 1.0))
        self.assertLess(ratio, self.rate * 1.25)
        self.assertTrue(stale_seen)
        self.assertFalse(any(stale_seen), 'state reported stale while the robot ran')

    def test_rospy_time_follows_the_clock(self):
        self._wait(lambda: self._latest() is not None, '/clock', DEADLINE_S)
        self._wait(lambda: rospy.get_time() > 0, 'rospy sim time', DEADLINE_S)
        _, sim = self._latest()
        self.assertAlmostEqual(rospy.get_time(), sim, delta=1.0)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'sim_time', SimTimeTest)
