#!/usr/bin/env python3
"""A simulated clamp straight, recorded by launch/record.launch and plotted
by plot_run, shows one marker per executed primitive.

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

from xmlrpc.client import ServerProxy

import rosgraph
import rosnode
import rospy
import rostest

import ready

from pirate import names
from pirate.msg import PirateAction, PirateGoal
from pirate.supervisory.goal_client_ros import SimpleGoalClient
from pirate.viz import plot_cli

# The repository (not the workspace's folder of links): results land in its test-results/.
PKG = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
RESULTS = os.path.join(PKG, 'test-results')
BAG = os.path.join(RESULTS, 'viz_clamp_straight.bag')
PNG = os.path.join(RESULTS, 'plot_clamp_straight.png')
#: Report Table 6.1: the simple clamp straight, starting straight.
SIMPLE_CLAMP_STRAIGHT = ['move front', 'clamp rear', 'clamp front']
FEEDBACK_TOPIC = names.PIRATE_ACTION + '/feedback'


RECORDER = '/record_run'
#: The recorder must be connected to these before the goal goes out, or the
#: first feedback (and the goal itself) is lost to the connection race.
RECORDED = (names.ROBOT_STATE_TOPIC, FEEDBACK_TOPIC, names.PIRATE_ACTION + '/goal')


def _recorder_connected(topics):
    """True once the recorder has a live inbound connection on every topic."""
    try:
        uri = rosnode.get_api_uri(rosgraph.Master('/viz_plot_clamp'), RECORDER, skip_cache=True)
        if not uri:
            return False
        _, _, bus = ServerProxy(uri).getBusInfo('/viz_plot_clamp')
    except (OSError, rosnode.ROSNodeIOException):
        return False
    # getBusInfo rows: [id, peer, direction, transport, topic, connected]
    live = {row[4] for row in bus if row[2] == 'i' and (len(row) < 6 or row[5])}
    return set(topics) <= live


class VizPlotClampTest(unittest.TestCase):

    def test_plot_of_a_recorded_clamp_straight(self):
        os.makedirs(RESULTS, exist_ok=True)
        for path in (BAG, PNG):
            if os.path.exists(path):
                os.remove(path)
        recorder = subprocess.Popen(['roslaunch', 'pirate', 'record.launch', 'bag:=' + BAG],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
            self.assertTrue(client.wait_for_server(rospy.Duration(60)), 'no Pirate Server')
            ready.wait_robot_connected(60)
            deadline = time.monotonic() + 60
            goal_pub = client.action_client.pub_goal   # server + recorder, from our side too
            while not (_recorder_connected(RECORDED) and goal_pub.get_num_connections() >= 2):
                self.assertLess(time.monotonic(), deadline, 'recorder never connected')
                self.assertIsNone(recorder.poll(), 'record.launch exited')
                time.sleep(0.2)   # poll interval of the node query
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
        self.assertTrue(0 <= times[0] and times[-1] <= run.times[-1],
                        'markers %s outside the recorded states 0..%.3f s (%d states)'
                        % (markers, run.times[-1], len(run.times)))
        # The clamp's guard lines are drawn and the bends reached them.
        front = drawn[1]
        self.assertTrue(front.guards, 'no guard lines on the clamp front panel')
        outer = min(v for _, v in front.guards)
        self.assertLessEqual(min(run.positions['bend_i']), outer)


if __name__ == '__main__':
    rospy.init_node('viz_plot_clamp')
    rostest.rosrun('pirate', 'viz_plot_clamp', VizPlotClampTest)
