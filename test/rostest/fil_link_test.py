#!/usr/bin/env python3
"""Firmware-in-the-loop link tests, measured on the simulated PICO bus.

Each test builds the chain itself: FirmwareInTheLoop (native firmware +
simulated boards) in this process, and serial_node as a child process on
the pty, so the test can SIGKILL it. The laptop side is this test
publishing setpoints at 10 Hz, as pirate.robot.commands.Setpoint.tick does.

- command loss: SIGKILL serial_node -> every board stopped within 300 ms of
  the last setpoint that reached the firmware;
- stall: the link passes nothing for 2 s, then recovers -> no board ever
  applies a setpoint that the laptop had replaced more than 200 ms before;
- unplug/replug: boards stop; after replug (a Mega reset) nothing moves
  until a setpoint arrives after the new handshake, then motion resumes.
"""
import signal
import sys
import time
import unittest

import rospy
import rostest

import fil_harness

BUDGET_S = 0.3
MAX_AGE_S = 0.2
BOARDS = fil_harness.BOARDS
wait_for = fil_harness.wait_for


class FilLinkTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.firmware, cls.serial_node = fil_harness.build()

    def setUp(self):
        self.fil = fil_harness.start_fil(self.firmware)
        self.link = self.fil.link_path
        self.host = self._spawn_host()
        self.laptop = fil_harness.Laptop(fil_harness.ros_sender())
        self.bus = fil_harness.Bus(self.fil)

    def tearDown(self):
        self.laptop.stop()
        fil_harness.stop_process(self.host)
        fil_harness.stop_fil(self.fil)

    def _spawn_host(self):
        return fil_harness.spawn_serial_node(self.serial_node, self.link)

    def _sets(self, board, since=0.0):
        return self.bus.sets(board, since)

    def _setpoint_frames(self, since=0.0):
        return self.bus.setpoint_frames(since)

    def _moving(self, since=0.0):
        return self.bus.moving(since)

    def test_sigkill_host_stops_every_board_within_budget(self):
        self.laptop.start()
        wait_for(self._moving, 20.0, 'all nine boards to get setpoints')
        time.sleep(0.5)   # mid-motion: several refresh cycles with setpoints
        self.host.send_signal(signal.SIGKILL)
        self.host.wait()
        killed = time.monotonic()
        wait_for(lambda: self.fil.boards.all_stopped_since(killed - 0.5) is not None
                 and time.monotonic() - killed > 0.6, 3.0, 'every board stopped')
        last_setpoint = self._setpoint_frames()[-1]
        stopped = self.fil.boards.all_stopped_since(last_setpoint)
        self.assertIsNotNone(stopped)
        delay = stopped - last_setpoint
        print('SIGKILL: all boards safe %.0f ms after the last setpoint' % (delay * 1000))
        self.assertLessEqual(delay, BUDGET_S)
        self.assertEqual(self._sets(20, stopped + 1e-6), [], 'a board moved after the stop')

    def test_stall_never_applies_a_stale_setpoint(self):
        self.laptop.start()
        wait_for(self._moving, 20.0, 'all nine boards to get setpoints')
        time.sleep(1.0)
        stall_start = time.monotonic()
        self.fil.stall(2.0)
        time.sleep(2.0)
        wait_for(lambda: self._sets(20, stall_start + 2.0), 5.0, 'setpoints after the stall')
        time.sleep(1.0)
        self.laptop.stop()
        stall_end = stall_start + 2.0
        log = list(self.fil.boards.log)
        for k in range(BOARDS):
            stops = [t for t, b, what, _ in log
                     if b == 20 + k and what == 'stop' and stall_start <= t <= stall_end]
            self.assertTrue(stops and stops[0] - stall_start <= BUDGET_S,
                            'board %d not stopped within budget in the stall' % (20 + k))
            self.assertEqual(self._sets(20 + k, stall_start + BUDGET_S)[:1],
                             self._sets(20 + k, stall_end)[:1],
                             'board %d moved during the stall' % (20 + k))
        worst = self.bus.worst_staleness(list(self.laptop.published))
        self.assertLessEqual(worst, MAX_AGE_S, 'a setpoint applied %.0f ms after the laptop '
                             'replaced it' % (worst * 1000))
        print('stall: worst setpoint staleness %.0f ms' % (worst * 1000))

    def test_unplug_stops_and_replug_needs_a_fresh_setpoint(self):
        self.laptop.start()
        wait_for(self._moving, 20.0, 'all nine boards to get setpoints')
        unplugged = time.monotonic()
        self.fil.unplug()
        wait_for(lambda: self.fil.boards.all_stopped_since(unplugged) is not None, 2.0,
                 'boards stopped after unplug')
        self.assertLessEqual(self.fil.boards.all_stopped_since(unplugged) - unplugged, BUDGET_S)
        time.sleep(0.5)
        replugged = time.monotonic()
        self.fil.replug()
        wait_for(lambda: self._moving(replugged), 20.0, 'motion after replug')
        first_set = min(t for k in range(BOARDS) for t, _ in self._sets(20 + k, replugged))
        first_setpoint = self._setpoint_frames(replugged)[0]
        self.assertGreaterEqual(first_set, first_setpoint,
                                'a board moved before a setpoint arrived after the reset')


if __name__ == '__main__':
    rospy.init_node('fil_link_test', anonymous=True)
    rostest.rosrun('pirate', 'fil_link', FilLinkTest, sys.argv)
