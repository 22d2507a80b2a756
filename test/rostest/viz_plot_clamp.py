#!/usr/bin/env python3
"""A simulated clamp straight, recorded by launch/record.launch and plotted
by plot_run, shows one marker per executed primitive (issue 6).

The robot starts upright, so the report's simple clamp straight runs (Table
6.1): move front, clamp rear, clamp front. The recorder is started through
record.launch as a child roslaunch (SIGINT closes the bag), the goal sent,
and once the result is in, the bag is plotted to test-results/.
"""
import os
import signal
import subprocess
import time
import unittest

import actionlib
import rosgraph
import rospkg
import rospy
import rostest

from pirate import names
from pirate.msg import PirateAction, PirateGoal
from pirate.viz import plot_cli

PKG = rospkg.RosPack().get_path('pirate')
RESULTS = os.path.join(PKG, 'test-results')
BAG = os.path.join(RESULTS, 'viz_clamp_straight.bag')
PNG = os.path.join(RESULTS, 'plot_clamp_straight.png')
#: Report Table 6.1: the simple clamp straight, starting straight.
SIMPLE_CLAMP_STRAIGHT = ['move front', 'clamp rear', 'clamp front']
FEEDBACK_TOPIC = names.PIRATE_ACTION + '/feedback'


def _subscribed(node, topic):
    """True once ``node`` subscribes ``topic`` (asked of the master)."""
    _, subscribers, _ = rosgraph.Master('/viz_plot_clamp').getSystemState()
    return any(t == topic and node in nodes for t, nodes in subscribers)


class VizPlotClampTest(unittest.TestCase):

    def test_plot_of_a_recorded_clamp_straight(self):
        os.makedirs(RESULTS, exist_ok=True)
        for path in (BAG, PNG):
            if os.path.exists(path):
                os.remove(path)
        recorder = subprocess.Popen(['roslaunch', 'pirate', 'record.launch', 'bag:=' + BAG],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            deadline = time.monotonic() + 60
            while not _subscribed('/record_run', FEEDBACK_TOPIC):
                self.assertLess(time.monotonic(), deadline, 'record_run never subscribed')
                self.assertIsNone(recorder.poll(), 'record.launch exited')
                time.sleep(0.2)   # poll interval of the master query
            client = actionlib.SimpleActionClient(names.PIRATE_ACTION, PirateAction)
            self.assertTrue(client.wait_for_server(rospy.Duration(60)), 'no Pirate Server')
            client.send_goal(PirateGoal(name=PirateGoal.CLAMP_STRAIGHT, pipe_diameter=90))
            self.assertTrue(client.wait_for_result(rospy.Duration(120)), 'no result')
            self.assertTrue(client.get_result().success, client.get_result().message)
        finally:
            recorder.send_signal(signal.SIGINT)
            recorder.wait(timeout=60)
        self.assertTrue(os.path.exists(BAG), 'record.launch wrote no bag')

        run, drawn, config_path = plot_cli.plot_bag(
            BAG, PNG, title='simulated simple clamp straight, 90 mm pipe')
        self.assertTrue(os.path.getsize(PNG) > 0)
        self.assertTrue(config_path.endswith('guards_90.yaml'), config_path)
        markers = run.markers
        self.assertEqual([p for _, p in markers], SIMPLE_CLAMP_STRAIGHT)
        times = [t for t, _ in markers]
        self.assertEqual(times, sorted(times))
        self.assertTrue(0 <= times[0] and times[-1] <= run.times[-1])
        # The clamp's guard lines are drawn and the bends reached them.
        front = drawn[1]
        self.assertTrue(front.guards, 'no guard lines on the clamp front panel')
        outer = min(v for _, v in front.guards)
        self.assertLessEqual(min(run.positions['bend_i']), outer)


if __name__ == '__main__':
    rospy.init_node('viz_plot_clamp')
    rostest.rosrun('pirate', 'viz_plot_clamp', VizPlotClampTest)
