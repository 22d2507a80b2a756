#!/usr/bin/env python3
"""A mission over ROS: refused routes, and a route paused during
its drive - by the operator panel disconnecting - and resumed from the
panel's M 4, that still ends at its target.

Waits on feedback and results (conditions), never on sleeps."""
import threading
import unittest

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from visualization_msgs.msg import Marker, MarkerArray

from ready import wait_robot_connected, wait_until
from pirate import names
from pirate.msg import MidiInput, MidiOutput, MissionAction, MissionGoal
from pirate.srv import MissionCommand, ServerStatus
from pirate.supervisory.goal_client_ros import SimpleGoalClient
from std_msgs.msg import String

WAIT_S = 120.0
PLAY, REWIND, M3_PAUSE, M4_RESUME = 41, 43, 50, 51


class Panel(object):
    """The test as the operator's panel: MIDI presses out, LEDs and the
    Mapper's words in; unplugged by unregistering its publisher."""

    def __init__(self):
        self.cond, self.leds, self.told = threading.Condition(), {}, []
        rospy.Subscriber(names.MIDI_OUTPUT_TOPIC, MidiOutput, self._on_led, queue_size=100)
        rospy.Subscriber(names.OPERATOR_TOPIC, String, self._on_told, queue_size=100)
        self.pub = None

    def _on_led(self, msg):
        with self.cond:
            self.leds[msg.button] = msg.value
            self.cond.notify_all()

    def _on_told(self, msg):
        with self.cond:
            self.told.append(msg.data)
            self.cond.notify_all()

    def wait(self, predicate, what):
        with self.cond:
            assert self.cond.wait_for(predicate, WAIT_S), '%s; told %s' % (what, self.told[-5:])

    def plug(self):
        """Publish panel events again; return once both ends have the connection (the
        Mapper's side, which it tells, can see it before ours can send on it)."""
        told = len(self.told)
        self.pub = rospy.Publisher(names.MIDI_INPUT_TOPIC, MidiInput, queue_size=10)
        self.wait(lambda: any(t.startswith('panel connected') for t in self.told[told:]), 'the Mapper sees the panel')
        wait_until(lambda: self.pub.get_num_connections() > 0, 'our panel publisher connected to the Mapper')

    def unplug(self):
        self.pub.unregister()

    def press(self, channel):
        self.pub.publish(MidiInput(channel=channel, value=127))
        self.pub.publish(MidiInput(channel=channel, value=0))


class MissionTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('mission_test')
        wait_robot_connected()
        cls.client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
        assert cls.client.wait_for_server(rospy.Duration(60))
        rospy.wait_for_service(names.MISSION_COMMAND_SERVICE, 60)
        cls.command = rospy.ServiceProxy(names.MISSION_COMMAND_SERVICE, MissionCommand)
        cls.status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
        cls.panel = Panel()
        cls.panel.plug()
        cls.panel.press(REWIND)           # PAB mode, then Play: the panel lets goals move the robot
        cls.panel.press(PLAY)
        cls.panel.wait(lambda: cls.panel.leds.get(PLAY), 'playing')

    def test_1_a_route_the_map_cannot_serve_is_refused_with_the_reason(self):
        self.client.send_goal(MissionGoal(map='straight_90', points=['pit', 'nowhere']))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(WAIT_S)))
        self.assertEqual(self.client.get_state(), GoalStatus.REJECTED)
        self.assertIn("no point 'nowhere'", self.client.get_result().message)
        self.assertFalse(self.status().active)        # nothing was sent to the Pirate Server

    def test_2_pause_during_the_drive_holds_and_resume_ends_at_the_target(self):
        cond, seen = threading.Condition(), []

        def feedback(fb):
            with cond:
                seen.append(fb)
                cond.notify_all()

        def wait_for(predicate):
            with cond:
                self.assertTrue(cond.wait_for(lambda: any(predicate(f) for f in seen), WAIT_S),
                                'no such feedback; seen %s' % [(f.step, f.pab, f.waiting_for) for f in seen[-5:]])

        poses, markers = [], []
        rospy.Subscriber(names.MISSION_POSE_TOPIC, PoseStamped, poses.append)
        rospy.Subscriber(names.MISSION_MARKERS_TOPIC, MarkerArray, markers.append)
        self.client.send_goal(MissionGoal(map='straight_90', points=['pit', 'target'], speed=30.0),
                              feedback_cb=feedback)
        wait_for(lambda f: f.pab == 'DRIVE' and f.state == 'running')
        self.panel.unplug()                          # the operator's panel is gone mid-mission
        wait_for(lambda f: f.waiting_for.startswith('resume'))
        status = self.status()
        self.assertFalse(status.active)              # the drive was cancelled: the robot is held
        self.assertEqual(self.command('jump').ok, False)
        self.panel.plug()
        self.panel.wait(lambda: self.panel.leds.get(M3_PAUSE), 'the pause LED lit while paused')
        self.panel.press(M4_RESUME)                  # resumed from the panel (PAB mode's M 4)
        self.assertTrue(self.client.wait_for_result(rospy.Duration(WAIT_S)))
        result = self.client.get_result()
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED, result.message)
        self.assertEqual(result.status, 'succeeded')
        self.assertTrue(any(line.startswith('pause') and 'operator panel disconnected' in line
                            for line in result.log), result.log)
        drives = [line for line in result.log if line.startswith('step') and 'DRIVE' in line]
        self.assertEqual(len(drives), 2, result.log)  # the drive, and what was left of it
        self.assertTrue(any(line.startswith('step') and 'HOME' in line for line in result.log))
        self.assertFalse(self.command('pause').ok)   # no mission runs any more
        # RViz: the route from pit (0.4 m) to target (0.9 m) along the straight's
        # axis (+x), the points named, and the estimate on the map between them
        route = [m for a in markers for m in a.markers if m.ns == 'route']
        self.assertTrue(route and route[0].type == Marker.LINE_STRIP)
        xs = [p.x for p in route[0].points]
        self.assertAlmostEqual(min(xs), 0.4, places=3)
        self.assertAlmostEqual(max(xs), 0.9, places=3)
        self.assertEqual(sorted(m.text for a in markers for m in a.markers if m.ns == 'points'), ['pit', 'target'])
        self.assertTrue(poses)
        for pose in poses:
            self.assertEqual(pose.header.frame_id, names.MAP_FRAME)
            self.assertTrue(0.38 <= pose.pose.position.x <= 0.92, pose.pose.position)
            self.assertAlmostEqual(pose.pose.position.y, 0.0, places=6)
        self.assertGreater(max(p.pose.position.x for p in poses), 0.8)   # it saw the robot near the target


if __name__ == '__main__':
    rostest.rosrun('pirate', 'mission_pause', MissionTest)
