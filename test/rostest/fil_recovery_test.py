#!/usr/bin/env python3
"""Recovery of the link through firmware in the loop, with both host kinds
(watchdog trip, stall, reset; board freshness and latched control), measured
on the simulated bus.

Hosts: our serial_node (a child process on the pty), and
RosserialPythonRules, which keeps rosserial_python's rules (topics
requested again only after 15 s without a time request, FIFO queue, no
re-send of latched values): it needed 15 s.

- trip (the laptop pauses its setpoints 1 s: Stop), 2.5 s stall, reset
  (cable in): setpoints reach the boards again within 1 s of the fault's
  end, with both hosts; after a reset the boards hold until the laptop's
  control array is there (ours re-sends it; with rosserial_python's rules
  the laptop must publish it again, and nothing moves until it does);
- 2 s and 10 s stalls with rosserial_python's FIFO (every queued setpoint
  replayed afterwards): no board applies a setpoint the laptop had replaced
  more than 200 ms before;
- control modes changed during a stall, or lost in a reset, are what
  the boards run afterwards; a muted board is logged once, by id.
"""
import sys
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log

import fil_harness
from fil_harness import Bus, Laptop, control_codes, wait_for
from pirate.link.rosserial_python_rules import RosserialPythonRules

RECOVERY_S = 1.0
MAX_AGE_S = 0.2
TORQUE = 2     # a control code other than the power-up PWM 0


class FilRecoveryTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.firmware, cls.serial_node = fil_harness.build()
        cls.rosout = []
        rospy.Subscriber('/rosout', Log, cls.rosout.append, queue_size=100)

    def setUp(self):
        self.fil = fil_harness.start_fil(self.firmware)
        self.bus = Bus(self.fil)
        self.ours = self.pyrules = None
        self.laptop = None

    def tearDown(self):
        if self.laptop:
            self.laptop.stop()
        if self.ours is not None:
            fil_harness.stop_process(self.ours)
        if self.pyrules is not None:
            self.pyrules.stop()
        fil_harness.stop_fil(self.fil)

    def _start(self, host, codes=None):
        if host == 'ours':
            self.ours = fil_harness.spawn_serial_node(self.serial_node, self.fil.link_path)
            self.laptop = Laptop(fil_harness.ros_sender())
        else:
            self.pyrules = RosserialPythonRules(self.fil.link_path)
            self.pyrules.start()
            wait_for(lambda: len(self.pyrules.subscriber_ids) == 3, 20.0, 'device subscribers')
            self.laptop = Laptop(fil_harness.direct_sender(self.pyrules))
        self.laptop.start(codes)
        wait_for(self.bus.moving, 30.0, 'all nine boards to get setpoints')

    def _recovery(self, since, what):
        wait_for(lambda: self.bus.first_set(since) is not None, 5.0, 'setpoints after ' + what)
        delay = self.bus.first_set(since) - since
        print('%s: first setpoint on the bus %.0f ms after the fault ended' % (what, delay * 1000))
        return delay

    # -- trip, stall, reset with both hosts ---------------------------------------
    def _trip(self, host):
        self._start(host)
        self.laptop.paused.set()                 # Stop: the setpoint stream ends
        paused = time.monotonic()
        wait_for(lambda: self.fil.boards.all_stopped_since(paused) is not None, 2.0, 'the trip')
        time.sleep(0.7)                          # the operator waits, then plays again
        resumed = time.monotonic()
        self.laptop.paused.clear()
        self.assertLessEqual(self._recovery(resumed, '%s trip' % host), RECOVERY_S)

    def test_trip_recovers_with_rosserial_python_rules(self):
        self._trip('pyrules')

    def test_trip_recovers_with_our_host(self):
        self._trip('ours')

    def _stall(self, host, seconds):
        self._start(host)
        self.fil.stall(seconds)
        ended = time.monotonic() + seconds
        wait_for(lambda: time.monotonic() > ended, seconds + 1, 'the stall')
        return ended

    def test_stall_2_5_s_recovers_with_rosserial_python_rules(self):
        ended = self._stall('pyrules', 2.5)
        self.assertLessEqual(self._recovery(ended, 'pyrules 2.5 s stall'), RECOVERY_S)

    def test_stall_2_5_s_recovers_with_our_host(self):
        ended = self._stall('ours', 2.5)
        self.assertLessEqual(self._recovery(ended, 'ours 2.5 s stall'), RECOVERY_S)

    def test_reset_recovers_with_our_host_in_the_laptops_modes(self):
        # the reset Mega forgets the control array; ours re-sends it
        self._start('ours', control_codes(TORQUE))
        reset = time.monotonic()
        self.fil.reset()
        self.assertLessEqual(self._recovery(reset, 'ours reset'), RECOVERY_S)
        wait_for(lambda: self.bus.sets(22, reset), 2.0, 'board 22 in its slot of the cycle')
        for t, command in self.bus.sets(22, reset):
            self.assertEqual(command.mode0, TORQUE, 'board 22 ran mode %d after the reset '
                             'while the laptop believed torque' % command.mode0)

    def test_reset_with_rosserial_python_rules_holds_until_control_comes(self):
        self._start('pyrules', control_codes(TORQUE))
        reset = time.monotonic()
        self.fil.reset()
        frames = len(self.pyrules.received)
        wait_for(lambda: len(self.pyrules.received) > frames + 9, RECOVERY_S,
                 'Small State again within 1 s of the reset')
        time.sleep(1.0)
        self.assertIsNone(self.bus.first_set(reset), 'a board moved before the control array')
        self.assertEqual(self.pyrules.lost_syncs, 0)
        again = time.monotonic()
        self.laptop.set_control(control_codes(TORQUE))
        self.assertLessEqual(self._recovery(again, 'pyrules reset, control published'),
                             RECOVERY_S)
        wait_for(lambda: self.bus.sets(22, again), 2.0, 'board 22 in its slot of the cycle')
        self.assertEqual(self.bus.sets(22, again)[0][1].mode0, TORQUE)

    # -- stale setpoints after stalls, rosserial_python's FIFO replaying all --------
    def _no_stale_after(self, seconds):
        ended = self._stall('pyrules', seconds)
        self._recovery(ended, 'pyrules %.0f s stall' % seconds)
        time.sleep(1.0)
        worst = self.bus.worst_staleness(list(self.laptop.published))
        print('%.0f s stall: worst setpoint staleness %.0f ms' % (seconds, worst * 1000))
        self.assertLessEqual(worst, MAX_AGE_S)

    def test_no_stale_setpoint_after_a_2_s_stall(self):
        self._no_stale_after(2.0)

    def test_no_stale_setpoint_after_a_10_s_stall(self):
        self._no_stale_after(10.0)

    # -- control and freshness across a stall ------------------------------------
    def test_control_changed_during_a_stall_is_what_the_boards_run(self):
        self._start('ours', control_codes(TORQUE))
        self.fil.stall(2.0)
        time.sleep(0.5)
        self.laptop.set_control(control_codes(0))   # the operator switches to PWM
        ended = time.monotonic() + 1.5
        wait_for(lambda: time.monotonic() > ended, 3.0, 'the stall')
        self._recovery(ended, 'ours stall with a control change')
        wait_for(lambda: self.bus.sets(22, ended), 2.0, 'board 22 in its slot of the cycle')
        modes = {command.mode0 for t, command in self.bus.sets(22, ended)}
        self.assertEqual(modes, {0}, 'board 22 ran modes %s after the stall; the laptop '
                                     'believes PWM (0)' % sorted(modes))

    def test_silent_board_logged_once_by_the_firmware(self):
        self._start('ours')
        self.fil.mute(22)
        wait_for(lambda: self._warnings('board 22 not answering'), 5.0, 'the firmware\'s warning')
        time.sleep(1.0)
        self.assertEqual(len(self._warnings('board 22 not answering')), 1)
        self.fil.mute(None)
        wait_for(lambda: self._warnings('board 22 answering again'), 5.0, 'the return')

    def _warnings(self, text):
        return [m for m in list(self.rosout) if text in m.msg
                and m.name.startswith('/serial_node')]


if __name__ == '__main__':
    rospy.init_node('fil_recovery_test', anonymous=True)
    rostest.rosrun('pirate', 'fil_recovery', FilRecoveryTest, sys.argv)
