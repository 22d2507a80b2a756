#!/usr/bin/env python3
"""rostest: the simulated robot's camera topics and the camera pan's state.

Runs against launch/robot.launch (sim_robot + pirate_state) in simulated
time. Every wait is on a condition with a wall-clock deadline, never a sleep.
"""
import unittest

import numpy
import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image, JointState

from pirate import names
from pirate.msg import ControlArray, SetpointArray
from pirate.robot import safety, tables, units
from ready import wait_until

PAN_RAD = 0.6


def arrays():
    """Play, both LEDs full, the camera pan to PAN_RAD in position mode."""
    setpoints, modes = [0] * tables.SETPOINT_SIZE, [safety.MODE_CODES['pwm']] * tables.CONTROL_SIZE
    modes[tables.element('rear_module').index] = safety.COMMAND_CODES['play']
    modes[tables.element('camera_pan').index] = safety.MODE_CODES['position']
    setpoints[tables.element('camera_pan').index] = units.rad_to_encoder(PAN_RAD)
    for led in ('front_led', 'rear_led'):
        setpoints[tables.element(led).index] = safety.DUTY_MAX
    return setpoints, modes


class SimCameraTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('sim_camera_test')
        cls.latest = {}
        for camera, namespace in names.CAMERA_NAMESPACES.items():
            rospy.Subscriber(namespace + '/image_raw', Image, cls._keep, (camera, 'image'), queue_size=1)
            rospy.Subscriber(namespace + '/camera_info', CameraInfo, cls._keep, (camera, 'info'), queue_size=1)
        rospy.Subscriber('/clock', Clock, cls._keep, ('clock', 'clock'), queue_size=1)
        rospy.Subscriber(names.JOINT_STATES_TOPIC, JointState, cls._keep, ('state', 'joints'), queue_size=1)
        setpoint = rospy.Publisher(names.SETPOINT_TOPIC, SetpointArray, queue_size=1)
        control = rospy.Publisher(names.CONTROL_TOPIC, ControlArray, queue_size=1)
        sent_setpoints, sent_modes = arrays()

        def send(_event):       # the Mega's watchdog wants a setpoint array every 0.25 s
            control.publish(ControlArray(data=sent_modes))
            setpoint.publish(SetpointArray(data=sent_setpoints))
        rospy.Timer(rospy.Duration(0.1), send)

    @classmethod
    def _keep(cls, msg, key):
        cls.latest[key] = msg

    def _clock_s(self):
        clock = self.latest.get(('clock', 'clock'))
        return clock.clock.to_sec() if clock else 0.0

    def test_1_each_camera_publishes_in_its_frame_on_the_simulated_clock(self):
        for camera in names.CAMERA_NAMESPACES:
            image = wait_until(lambda: self.latest.get((camera, 'image')), '%s image' % camera)
            info = wait_until(lambda: self.latest.get((camera, 'info')), '%s camera info' % camera)
            self.assertEqual(image.header.frame_id, names.CAMERA_FRAMES[camera])
            self.assertEqual(info.header.frame_id, names.CAMERA_FRAMES[camera])
            stamp = image.header.stamp.to_sec()
            self.assertTrue(0 < stamp < 1e6, 'stamp %.1f s is not on the simulated clock' % stamp)
            # the clock goes on from the stamp (topics arrive in any order: wait for the clock to pass it)
            clock = wait_until(lambda: self._clock_s() >= stamp and self._clock_s(), 'the clock at the stamp')
            self.assertLess(clock - stamp, 5.0)
            self.assertEqual((info.width, info.height), (image.width, image.height))
            self.assertEqual(len(image.data), image.width * image.height * 3)

    def test_2_the_leds_light_the_images(self):
        def lit():
            image = self.latest.get(('front', 'image'))
            return image is not None and numpy.frombuffer(image.data, numpy.uint8).mean() > 10
        wait_until(lit, 'a lit front image')

    def test_3_the_state_reports_the_pan_sent(self):
        def pan():
            joints = self.latest.get(('state', 'joints'))
            return joints is not None and abs(joints.position[joints.name.index('camera_pan')] - PAN_RAD) < 0.01
        wait_until(pan, 'camera_pan at %.1f rad in /joint_states' % PAN_RAD)


if __name__ == '__main__':
    rostest.rosrun('pirate', 'sim_camera', SimCameraTest)
