#!/usr/bin/env python3
"""RViz renders the simulated robot rolled in its pipe.

Checks, in order: the state node's joint states name exactly the URDF's
moving joints; TF holds pipe -> base_link rolled
by the simulated orientation (REP 103 roll = pi/2 - orientation) and
placed along the pipe's axis at the odometry; the pipe
marker has the pipe's diameter; the text beside the robot says its
odometry; and, on a private Xvfb display, RViz with
rviz/pirate.rviz draws the robot's orange modules. The screenshot is saved
to test-results/rviz_screenshot.png whatever the outcome.
"""
import math
import os
import shutil
import subprocess
import time
import unittest

import numpy
import rospy
import rostest
import tf2_ros
from PIL import ImageGrab
from sensor_msgs.msg import JointState
from visualization_msgs.msg import Marker, MarkerArray

from pirate import names
from pirate.msg import RobotState
from pirate.viz import urdf_gen

# The repository (not the workspace's folder of links): results land in its test-results/.
PKG = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SCREENSHOT = os.path.join(PKG, 'test-results', 'rviz_screenshot.png')
RENDER_TIMEOUT_S = 120.0     # software OpenGL on a shared 2-core machine
ORANGE_MIN_PIXELS = 1500     # the seven modules at the configured view


def orange_pixels(rgb):
    """Pixels of the URDF's pirate_orange, lit or shaded (R high, B low)."""
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return int(numpy.count_nonzero((r >= 110) & (g >= 0.25 * r) & (g <= 0.75 * r)
                                   & (b <= 0.45 * r)))


class VizRvizTest(unittest.TestCase):

    def setUp(self):
        self.procs = []

    def tearDown(self):
        for proc in reversed(self.procs):
            proc.terminate()
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()

    def test_tf_marker_and_render(self):
        orientation = rospy.get_param('~orientation')
        joints = rospy.wait_for_message(names.JOINT_STATES_TOPIC, JointState, timeout=30)
        # Every joint the state node publishes is in the URDF, and vice versa.
        self.assertEqual(set(joints.name),
                         urdf_gen.moving_joints(rospy.get_param('/robot_description')))

        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        tf = buffer.lookup_transform('pipe', 'base_link', rospy.Time(0), rospy.Duration(30))
        q = tf.transform.rotation
        roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x ** 2 + q.y ** 2))
        self.assertAlmostEqual(roll, math.pi / 2 - orientation, delta=0.05)
        state = rospy.wait_for_message(names.ROBOT_STATE_TOPIC, RobotState, timeout=30)
        self.assertAlmostEqual(tf.transform.translation.x, state.odometry / 1000.0, delta=0.005)
        # The wrist links come from robot_state_publisher: the URDF is loaded.
        buffer.lookup_transform('base_link', 'camera_link', rospy.Time(0), rospy.Duration(30))

        marker = rospy.wait_for_message('/pirate_viz/pipe_marker', Marker, timeout=30)
        self.assertEqual(marker.type, Marker.CYLINDER)
        self.assertAlmostEqual(marker.scale.x, rospy.get_param('~pipe_diameter') / 1000.0)
        self.assertLess(marker.color.a, 1.0)
        position = rospy.wait_for_message('/pirate_viz/position_markers', MarkerArray, timeout=30)
        texts = [m.text for m in position.markers if m.ns == 'position']
        self.assertEqual(texts, ['odometry %d mm' % round(state.odometry)])

        if shutil.which('Xvfb') is None:
            self.skipTest('Xvfb missing (Debian package xvfb): the render is not checked')
        display = self._start_xvfb()
        env = dict(os.environ, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE='1')
        self.procs.append(subprocess.Popen(
            ['rosrun', 'rviz', 'rviz', '-d', os.path.join(PKG, 'rviz', 'pirate.rviz'),
             '__name:=viz_test_rviz'], env=env,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))

        count, image = self._wait_for_robot(display)
        os.makedirs(os.path.dirname(SCREENSHOT), exist_ok=True)
        image.save(SCREENSHOT)
        self.assertGreaterEqual(count, ORANGE_MIN_PIXELS,
                                'robot not rendered (%d orange pixels), see %s'
                                % (count, SCREENSHOT))

    def _start_xvfb(self):
        """Start Xvfb on a display it picks itself (-displayfd); return ':N'."""
        read_fd, write_fd = os.pipe()
        proc = subprocess.Popen(['Xvfb', '-displayfd', str(write_fd), '-screen', '0',
                                 '1024x768x24', '-nolisten', 'tcp'], pass_fds=(write_fd,),
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.procs.append(proc)
        os.close(write_fd)
        with os.fdopen(read_fd) as pipe:
            number = pipe.readline().strip()
        self.assertTrue(number.isdigit(), 'Xvfb did not report a display')
        return ':' + number

    def _wait_for_robot(self, display):
        """Screenshots until the robot's colour shows or the time is up."""
        deadline = time.monotonic() + RENDER_TIMEOUT_S
        while True:
            image = ImageGrab.grab(xdisplay=display)
            count = orange_pixels(numpy.asarray(image))
            if count >= ORANGE_MIN_PIXELS or time.monotonic() > deadline:
                return count, image
            self.assertIsNone(self.procs[-1].poll(), 'rviz exited')
            time.sleep(1.0)   # poll interval, not synchronisation


if __name__ == '__main__':
    rospy.init_node('viz_rviz_test')
    rostest.rosrun('pirate', 'viz_rviz', VizRvizTest)
