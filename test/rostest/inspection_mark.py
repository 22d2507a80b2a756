#!/usr/bin/env python3
"""rostest: /pirate/inspection/mark records a finding where the robot is,
with both cameras' frames (latched here: the recorder asks each camera at
the mark), in the run folder, and the findings topic (latched) shows it; a
bad kind records nothing.

With ``~mission_map`` the recorder starts without a map: a mark is refused
("no map") until the mission executive's latched current mission
(``/pirate/mission/current``) names that map, whenever the recorder
subscribed; the estimate heard before it stands."""
import json
import math
import os
import threading
import time
import unittest

import rospy
import rostest
from sensor_msgs.msg import Image
from std_msgs.msg import Float64, String

from pirate import names
from pirate.msg import MissionActionGoal, RobotState
from pirate.srv import InspectionMark

DEADLINE_S = 60.0
POLL_S = 0.05
WIDTH, HEIGHT = 16, 12


def _image(encoding, pixel):
    return Image(width=WIDTH, height=HEIGHT, encoding=encoding, step=WIDTH * 3, data=bytes(pixel) * (WIDTH * HEIGHT))


class InspectionMarkTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('inspection_mark_test')
        cls.findings, cls.changed = None, threading.Condition()
        rospy.Subscriber(names.INSPECTION_FINDINGS_TOPIC, String, cls._on_findings)
        latched = dict(queue_size=1, latch=True)
        cls.state = rospy.Publisher(names.ROBOT_STATE_TOPIC, RobotState, **latched)
        cls.front = rospy.Publisher(names.CAMERA_NAMESPACES['front'] + '/image_raw', Image, **latched)
        cls.rear = rospy.Publisher(names.CAMERA_NAMESPACES['rear'] + '/image_raw', Image, **latched)
        cls.uncertainty = rospy.Publisher(names.MISSION_UNCERTAINTY_TOPIC, Float64, **latched)
        cls.along = rospy.Publisher(names.MISSION_ALONG_TOPIC, Float64, **latched)
        cls.mission = rospy.Publisher(names.MISSION_CURRENT_TOPIC, MissionActionGoal, **latched)
        rospy.wait_for_service(names.INSPECTION_MARK_SERVICE, timeout=DEADLINE_S)
        cls.mark = rospy.ServiceProxy(names.INSPECTION_MARK_SERVICE, InspectionMark)

    @classmethod
    def _on_findings(cls, msg):
        with cls.changed:
            cls.findings = json.loads(msg.data)
            cls.changed.notify_all()

    def _wait(self, what, predicate):
        with self.changed:
            self.assertTrue(self.changed.wait_for(predicate, DEADLINE_S), 'waited for %s' % what)

    def _heard(self, publisher):
        deadline = time.monotonic() + DEADLINE_S
        while publisher.get_num_connections() == 0:
            self.assertLess(time.monotonic(), deadline, 'waited for %s to be heard' % publisher.resolved_name)
            time.sleep(POLL_S)

    def test_a_mark_records_the_place_and_both_frames(self):
        self._wait('the findings of the new run', lambda: self.findings is not None)
        self.assertEqual(self.findings['findings'], [])
        for publisher in (self.state, self.uncertainty, self.along):     # the cameras are asked at each mark
            self._heard(publisher)
        self.state.publish(RobotState(name=['camera_tilt', 'camera_pan'], position=[0.6, 0.0],
                                      orientation=math.pi / 2, odometry=0.0))
        self.front.publish(_image('rgb8', (200, 40, 40)))
        self.rear.publish(_image('bgr8', (40, 40, 200)))
        expected = "1990 mm from the launch pit (+/- 170 mm), 12 o'clock"
        self._mission_names_the_map(rospy.get_param('~mission_map', ''))
        answer = None
        for _ in range(50):       # until the node has heard the state, the estimate and the map (in flight)
            self.uncertainty.publish(Float64(data=170.0))
            self.along.publish(Float64(data=2390.0))
            rospy.sleep(0.1)
            answer = self.mark(kind='leak', note='hiss')
            if expected in answer.message or not (answer.ok or 'no map' in answer.message):
                break
        self.assertTrue(answer.ok, answer.message)
        self.assertIn(expected, answer.message)
        self._wait('the finding on the topic', lambda: any(
            f['note'] == 'hiss' and f['position']['along_mm'] == 2390.0 for f in self.findings['findings']))
        last = self.findings['findings'][-1]
        self.assertEqual(sorted(last['frames']), ['front', 'rear'])
        self.assertEqual(last['source'], rospy.get_name())
        for name in last['frames'].values():
            self.assertGreater(os.path.getsize(os.path.join(self.findings['run'], name)), 0)
        refused = self.mark(kind='hole', note='')
        self.assertFalse(refused.ok)
        self.assertIn('not one of', refused.message)

    def _mission_names_the_map(self, map_name):
        """Without a map a mark is refused; then the latched current mission names ``map_name``."""
        if not map_name:
            return
        refused = self.mark(kind='leak', note='before the mission')
        self.assertFalse(refused.ok)
        self.assertIn('no map', refused.message)
        current = MissionActionGoal()
        current.header.stamp = rospy.Time.now()
        current.goal_id.id = 'inspection-mark-rostest'
        current.goal.map, current.goal.points = map_name, ['launch_pit', 'target']
        self.mission.publish(current)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'inspection_mark', InspectionMarkTest)
