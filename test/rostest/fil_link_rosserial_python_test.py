#!/usr/bin/env python3
"""rosserial_python as the host of the Pirate Bay, through firmware in the
loop: the manager brings the laptop's command state back after a reset.

The host is :class:`pirate.link.rosserial_python_rules.RosserialPythonRules`
(FIFO queue, no re-send of latched values, topics requested again only
after 15 s without a time request); this script is its ROS side, as
rosserial_python's node is: the manager's three arrays go to the device,
the device's Small State is published. pirate_manager runs without a panel
and gets no goal, so it sends no setpoint and its limits only as its link
watch decides.

- The Mega resets (cable in; the native firmware restarts within one
  Small State cycle, so no silence shows): the laptop's control array and
  limits reach the firmware within the link watch's refresh, before any
  setpoint; the first setpoint sent then is applied by the boards in the
  laptop's modes and limits (the firmware holds the boards until control
  and limits are both back).
- /diagnostics_agg: the Link group is OK, not Stale, with this host.
"""
import io
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus

import fil_harness
from fil_harness import Bus, wait_for
from pirate import names
from pirate.msg import ControlArray, LimitArray, SetpointArray, SmallState
from pirate.link.rosserial_python_rules import RosserialPythonRules, serialise
from pirate.robot import link_watch

STATE_BACK_S = link_watch.REFRESH_S + 0.5     # the refresh, and the firmware's restart
SETPOINT, CONTROL, LIMITS = 101, 102, 103      # the firmware's topic ids (firmware/README.md)
ARRAYS = ((names.SETPOINT_TOPIC, SetpointArray), (names.CONTROL_TOPIC, ControlArray),
          (names.LIMITS_TOPIC, LimitArray))


class RosSide(object):
    """rosserial_python's ROS side around the rules host: subscribers that
    queue the laptop's arrays, a publisher of the device's Small State."""

    def __init__(self, host):
        self.host = host
        self.latest = {}
        self._small_state = rospy.Publisher(names.SMALL_STATE_TOPIC, SmallState, queue_size=50)
        self._stop = threading.Event()
        for name, kind in ARRAYS:
            rospy.Subscriber(name, kind, self._forward, name, queue_size=10)
        self._pump = threading.Thread(target=self._publish_small_state)
        self._pump.daemon = True
        self._pump.start()

    def _forward(self, msg, name):
        self.latest[name] = serialise(msg)
        self.host.publish(name, self.latest[name])

    def _publish_small_state(self):
        done = 0
        while not self._stop.wait(0.005):
            received = self.host.received[done:]
            done += len(received)
            for _, name, payload in received:
                if name == names.SMALL_STATE_TOPIC:
                    msg = SmallState()
                    msg.deserialize(payload)
                    self._small_state.publish(msg)

    def stop(self):
        self._stop.set()
        self._pump.join(1.0)


class FilLinkRosserialPythonTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('fil_link_rosserial_python_test')
        cls.firmware, _ = fil_harness.build()
        cls.agg = {}
        rospy.Subscriber('/diagnostics_agg', DiagnosticArray, lambda msg: cls.agg.update(
            (s.name, s) for s in msg.status), queue_size=5)

    def setUp(self):
        self.fil = fil_harness.start_fil(self.firmware)
        self.bus = Bus(self.fil)
        self.host = RosserialPythonRules(self.fil.link_path)
        self.host.start()
        self.side = RosSide(self.host)
        wait_for(lambda: len(self.host.subscriber_ids) == 3, 20.0, 'device subscribers')

    def tearDown(self):
        self.side.stop()
        self.host.stop()
        fil_harness.stop_fil(self.fil)

    def _frames(self, topic, since):
        return [(t, payload) for t, tid, payload in list(self.fil.host_frames)
                if tid == topic and t >= since]

    def _state_back(self, since, what):
        """Wait until control and limits reached the firmware after ``since``;
        return the time the later of the two arrived."""
        wait_for(lambda: self._frames(CONTROL, since) and self._frames(LIMITS, since),
                 STATE_BACK_S, 'control and limits at the firmware ' + what)
        return max(self._frames(CONTROL, since)[0][0], self._frames(LIMITS, since)[0][0])

    def test_reset_brings_control_and_limits_back_before_any_setpoint(self):
        self._state_back(0.0, 'at start')
        time.sleep(0.5)
        reset = time.monotonic()
        self.fil.reset()
        back = self._state_back(reset, 'after the reset')
        print('control and limits back %.0f ms after the reset' % ((back - reset) * 1000))
        self.assertEqual(self._frames(SETPOINT, reset), [], 'a setpoint before control/limits')
        self.assertEqual(self._frames(CONTROL, reset)[-1][1], self.side.latest[names.CONTROL_TOPIC])
        self.assertEqual(self._frames(LIMITS, reset)[-1][1], self.side.latest[names.LIMITS_TOPIC])
        self.assertEqual(self.host.lost_syncs, 0)
        # the first setpoint after them is run in the laptop's modes and limits
        sent = time.monotonic()
        control = ControlArray()
        control.deserialize(self.side.latest[names.CONTROL_TOPIC])
        limits = LimitArray()
        limits.deserialize(self.side.latest[names.LIMITS_TOPIC])
        while not self.bus.sets(22, sent) and time.monotonic() < sent + 2.0:
            self.host.publish(names.SETPOINT_TOPIC, serialise(SetpointArray(data=[0] * 13)))
            time.sleep(0.1)
        applied = self.bus.sets(22, sent)
        self.assertTrue(applied, 'board 22 still held 2 s after control, limits and setpoints')
        self.assertEqual(applied[0][1].mode0, control.data[2])   # board 22: Bend I (firmware/README.md)
        self.assertEqual(applied[0][1].limit, limits.data[0])

    def test_link_group_is_not_stale_with_rosserial_python_rules(self):
        self._state_back(0.0, 'at start')

        def link_ok():
            status = self.agg.get('/Link')
            return status is not None and status.level == DiagnosticStatus.OK
        wait_for(link_ok, 20.0, 'the Link group OK in /diagnostics_agg')
        self.assertIn('/Link/pirate_state: Small State', self.agg)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'fil_link_rosserial_python', FilLinkRosserialPythonTest)
