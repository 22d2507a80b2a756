#!/usr/bin/env python3
"""RViz shows the physics twin's pipe network and the robot at its true pose.

The manager clamps the robot straight in network_90 (Table 6.1's
sequence); then: the pipe markers are every piece of the world file
(translucent); the robot markers sit where the physics puts the modules,
both V apex wheels at the pipe wall; and on a private Xvfb display RViz
with rviz/world.rviz draws the network (blue) and the robot (orange). The
screenshot is saved to test-results/world_screenshot.png whatever the
outcome.
"""
import math
import os
import time

import numpy
import rospy
import rostest
from visualization_msgs.msg import MarkerArray

import ready
import viz_rviz
from pirate import names
from pirate.msg import PirateAction, PirateGoal
from pirate.supervisory.goal_client_ros import SimpleGoalClient
from pirate.world.network import world_path
from pirate.viz import world_markers
from pirate.world import network

SCREENSHOT = os.path.join(viz_rviz.PKG, 'test-results', 'world_screenshot.png')
BLUE_MIN_PIXELS = 3000


def blue_pixels(rgb):
    """Pixels of the translucent pipe over the dark background (B above R)."""
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return int(numpy.count_nonzero((b >= 70) & (b >= r + 15)))


class SimWorldRvizTest(viz_rviz.VizRvizTest):
    test_tf_marker_and_render = None          # the fitted robot's checks are viz_rviz's

    def test_world_and_true_pose(self):
        ready.wait_robot_connected()
        client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(60)))
        client.send_goal(PirateGoal(name=0, pipe_diameter=90))
        self.assertTrue(client.wait_for_result(rospy.Duration(120)))
        self.assertTrue(client.get_result().success, client.get_result().message)

        world = network.load(world_path('network_90'))
        pipes = rospy.wait_for_message('/world_viz/pipes', MarkerArray, timeout=30)
        self.assertEqual(len(pipes.markers), len(world_markers.pipe_shapes(world)))
        self.assertTrue(all(m.color.a < 1.0 for m in pipes.markers))
        radius = world.pieces[0].diameter / 2
        # The outer bends keep pressing after their guards: wait (on the
        # markers, up to a wall bound) until both V apexes touch the ceiling.
        deadline = time.monotonic() + 60.0
        while True:
            robot = rospy.wait_for_message('/world_viz/robot', MarkerArray, timeout=30)
            wheels = [m for m in robot.markers if m.color.r < 0.2]
            tops = sorted(wheels, key=lambda m: m.pose.position.z)[-2:]
            gaps = [radius - (top.pose.position.z + top.scale.x / 2) for top in tops]
            if max(abs(g) for g in gaps) <= 0.004 or time.monotonic() > deadline:
                break
        self.assertEqual(len(wheels), 6)
        self.assertLessEqual(max(abs(g) for g in gaps), 0.004, 'apex wheels off the wall by %s m' % gaps)
        for wheel in wheels:                   # every wheel inside the first straight's wall
            off_axis = math.hypot(wheel.pose.position.y, wheel.pose.position.z)
            self.assertLessEqual(off_axis + wheel.scale.x / 2, radius + 0.003)

        display = self._start_xvfb()
        env = dict(os.environ, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE='1')
        self.procs.append(viz_rviz.subprocess.Popen(
            ['rosrun', 'rviz', 'rviz', '-d', os.path.join(viz_rviz.PKG, 'rviz', 'world.rviz'),
             '__name:=world_test_rviz'], env=env,
            stdout=viz_rviz.subprocess.DEVNULL, stderr=viz_rviz.subprocess.DEVNULL))
        count, image = self._wait_for_robot(display)
        os.makedirs(os.path.dirname(SCREENSHOT), exist_ok=True)
        image.save(SCREENSHOT)
        self.assertGreaterEqual(count, viz_rviz.ORANGE_MIN_PIXELS, 'robot not rendered, see %s' % SCREENSHOT)
        self.assertGreaterEqual(blue_pixels(numpy.asarray(image)), BLUE_MIN_PIXELS,
                                'pipe network not rendered, see %s' % SCREENSHOT)


if __name__ == '__main__':
    rospy.init_node('sim_world_rviz_test')
    rostest.rosrun('pirate', 'sim_world_rviz', SimWorldRvizTest)
