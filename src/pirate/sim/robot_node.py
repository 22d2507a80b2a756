"""ROS edge of the simulated robot: the "simulated serial node".

Takes the place of serial link, Mega, PICO boards and robot. Subscribes the
three command arrays as the Mega does and publishes one raw Small State per
board every Mega refresh cycle (10 Hz, SPEC 2), while the model steps at the
PICO loop rate (50 Hz).

Time (doc/clock.md): with ``use_sim_time`` (every launch of the simulated
robot) the node owns ``/clock`` and advances it by at most ``~rate``
simulated seconds per wall second, in lockstep with the stack: after each
Mega cycle's states it waits until the manager acknowledges a state
(:mod:`pirate.sim.lockstep`, at most ``~lockstep_bound`` wall s). Without
``use_sim_time`` it runs in wall time, ``~rate`` 1, no lockstep.

The Mega's watchdog (:mod:`pirate.sim.watchdog`) stops every board when no
setpoint array arrives for 0.25 s of the simulated robot's time, as the
firmware does on its own clock.

Private params: ``~world`` (a world file or a name under config/worlds/:
the pipe network of the physics twin; empty: the straight pipe of
``~pipe_diameter``), ``~pipe_diameter`` (mm, 90 or 110), ``~orientation`` (rad,
start roll, Fig 4.7), ``~joints`` (dict joint -> rad, start angles: the
robot is moved across the pipe to where they fit, :mod:`pirate.sim.twin_start`),
``~seed`` (sensor noise seed, -1 none), ``~rate`` (real-time factor),
``~camera_rate`` (images per simulated second of each camera, 0: none;
``~camera_width``, ``~camera_height`` in pixels; defaults: config/twin.yaml
``cameras``). The front and rear cameras (:mod:`pirate.sim.twin_camera`)
are rendered only while someone subscribes, stamped on the simulated clock.
``~lockstep_bound`` (wall s the simulator waits for the stack per cycle).
The robot is always the physics twin (:mod:`pirate.sim.robot_end`); a bad
world, diameter or start pose ends the node with its reason (exit 1).
"""
import os
import threading
import time

import rospy
from geometry_msgs.msg import Pose, PoseArray
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import CameraInfo, Image
from std_msgs.msg import Time

from pirate import names
from pirate.camera.images_ros import CameraStreams
from pirate.robot import tables
from pirate.msg import ControlArray, LimitArray, SetpointArray, SmallState
from pirate.sim import robot_end
from pirate.sim.lockstep import WAIT_BOUND_S, Lockstep
from pirate.sim.watchdog import MegaWatchdog

PICO_PERIOD_S = 0.02    # PICO control loops, 50 Hz
MEGA_PERIOD_S = 0.1     # Mega refresh of all nine boards, about 10 Hz
CLOCK_START_S = 1.0     # sim time 0 means "no clock yet" to rospy


class SimRobotNode(object):
    """Wires a simulated robot (pirate.sim.robot_end) to the topics a real Mega uses."""

    def __init__(self):
        self.model = robot_end.of_node(rospy.get_param, rospy.logfatal)
        self.rate = float(rospy.get_param('~rate', 1.0))
        self.sim_time = rospy.get_param('/use_sim_time', False)
        if self.rate <= 0 or (not self.sim_time and self.rate != 1.0):
            rospy.logwarn('~rate %.2f needs use_sim_time and > 0; running in real time', self.rate)
            self.rate = 1.0
        self._lock = threading.Lock()
        self._arrays = [list(self.model.setpoints), list(self.model.modes), list(self.model.limits)]
        self._logged = set()
        self.watchdog = MegaWatchdog()
        self._sim_s = CLOCK_START_S     # the simulated robot's time: the Mega watchdog's clock
        self.lockstep = Lockstep(float(rospy.get_param('~lockstep_bound', WAIT_BOUND_S)))
        self._ack_sub = (rospy.Subscriber(names.LOCKSTEP_TOPIC, Time,
                                          lambda msg: self.lockstep.acknowledged(msg.data.to_sec()))
                         if self.sim_time else None)
        self._state_pub = rospy.Publisher(names.SMALL_STATE_TOPIC, SmallState, queue_size=len(tables.BOARDS) * 4)
        self._clock_pub = rospy.Publisher('/clock', Clock, queue_size=1) if self.sim_time else None
        self._truth_pub = (rospy.Publisher(names.GROUND_TRUTH_TOPIC, PoseArray, queue_size=2)
                           if hasattr(self.model, 'ground_truth_poses') else None)
        self.cameras = self._camera_streams()
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self._store, 0, queue_size=10)
        rospy.Subscriber(names.CONTROL_TOPIC, ControlArray, self._store, 1, queue_size=10)
        rospy.Subscriber(names.LIMITS_TOPIC, LimitArray, self._store, 2, queue_size=10)

    def _camera_streams(self):
        """The twin's cameras as topics, or None (``~camera_rate`` 0)."""
        cfg = self.model.config['cameras']
        rate_hz = float(rospy.get_param('~camera_rate', cfg['rate_hz']))
        self._camera_size = (int(rospy.get_param('~camera_width', cfg['width_px'])),
                             int(rospy.get_param('~camera_height', cfg['height_px'])))
        if rate_hz <= 0:
            return None
        pubs = {camera: (rospy.Publisher(ns + '/image_raw', Image, queue_size=2),
                         rospy.Publisher(ns + '/camera_info', CameraInfo, queue_size=2))
                for camera, ns in names.CAMERA_NAMESPACES.items()}
        self._renderer = None
        return CameraStreams(pubs, self._render, 1.0 / rate_hz, cfg['fovy_deg'])

    def _render(self, camera):
        """One camera's image; the renderer is made in the stepping thread, on first use."""
        if self._renderer is None:
            from pirate.sim.twin_camera import TwinCameras
            self._renderer = TwinCameras(self.model, *self._camera_size)
        return self._renderer.render(camera)

    def _publish_images(self, sim_t):
        stamp = rospy.Time.from_sec(sim_t) if self.sim_time else rospy.Time.now()
        try:
            self.cameras.tick(sim_t, stamp)
        except Exception as failed:     # no GL on this machine: the robot runs on without cameras
            rospy.logerr('sim_robot: cannot render the cameras (MUJOCO_GL=%s): %s; no images',
                         os.environ.get('MUJOCO_GL'), failed)
            self.cameras = None

    def _store(self, msg, which):
        with self._lock:
            self._arrays[which] = list(msg.data)
            if which == 0:
                self.watchdog.setpoint_arrived(self._sim_s)
            reasons = self._command()
        self._log_once(reasons)

    def _command(self):
        """Hand the arrays to the boards as the Mega would (STOP while disarmed)."""
        setpoints, modes, limits = self._arrays
        return self.model.command(setpoints, self.watchdog.boards_see(modes), limits)

    def _log_once(self, reasons):
        for reason in reasons:
            if reason not in self._logged:
                self._logged.add(reason)
                rospy.logwarn('sim_robot: %s', reason)

    def _publish_states(self):
        if self._ack_sub is not None:
            self.lockstep.published(self._sim_s)   # before the first state: its acknowledgement may be quick
        for board in tables.BOARDS:
            self._state_pub.publish(SmallState(board=board, data=self.model.small_state(board)))
        if self._truth_pub:
            self._truth_pub.publish(_pose_array(self.model.ground_truth_poses()))

    def _consumed(self):
        """Wait (bounded) until the stack took in the cycle just published."""
        if self._ack_sub is not None and not self.lockstep.wait(self._consumers):
            rospy.logwarn_throttle(10.0, 'sim_robot: the stack did not take a state in within %.1f s: '
                                   'stepping on (%d times; its newest acknowledgement stamped %.2f s before '
                                   'the cycle)', self.lockstep.bound_s, self.lockstep.overruns,
                                   self.lockstep.lag_s if self.lockstep.lag_s is not None else float('nan'))

    def _consumers(self):
        """Someone takes the states in and acknowledges them (a dead node drops its connection)."""
        return self._ack_sub.get_num_connections() > 0 and self._state_pub.get_num_connections() > 0

    def spin(self):
        """Step the model; publish /clock every step, the states every Mega
        cycle, then wait for the stack to take them in."""
        steps_per_cycle = int(round(MEGA_PERIOD_S / PICO_PERIOD_S))
        wall_next = time.monotonic()
        rospy.loginfo('sim_robot: %d mm pipe, roll %.2f rad, rate x%.1f%s',
                      round(self.model.pipe_diameter_m * 1000), self.model.rear_roll, self.rate,
                      ' (sim time)' if self.sim_time else '')
        step = 0
        while not rospy.is_shutdown():
            with self._lock:
                if self.watchdog.poll(self._sim_s):
                    self._command()
                    rospy.logwarn('sim_robot: no setpoint array for %.2f s: every board stopped '
                                  '(Mega watchdog)', self.watchdog.timeout_s)
                self.model.step(PICO_PERIOD_S)
                self._sim_s += PICO_PERIOD_S
            step += 1
            if self._clock_pub:
                self._clock_pub.publish(Clock(clock=rospy.Time.from_sec(self._sim_s)))
            if step % steps_per_cycle == 0:
                self._publish_states()
                self._consumed()
            if self.cameras:
                self._publish_images(self._sim_s)
            wall_next += PICO_PERIOD_S / self.rate
            delay = wall_next - time.monotonic()
            if delay > 0:
                time.sleep(delay)       # this node is the clock: it paces on the wall
            elif delay < -0.5:
                wall_next = time.monotonic()   # fell behind (a slow stack); do not try to catch up
        if self._ack_sub is not None:
            rospy.loginfo('sim_robot: lockstep: %d cycles stepped on unacknowledged; acknowledgements up to '
                          '%.2f s behind their cycle', self.lockstep.overruns, self.lockstep.worst_lag_s)


def _pose_array(poses):
    """PoseArray in the world frame from [(xyz, wxyz)]."""
    msg = PoseArray()
    msg.header.stamp = rospy.Time.now()
    msg.header.frame_id = 'world'
    for (x, y, z), (qw, qx, qy, qz) in poses:
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = x, y, z
        pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z = qw, qx, qy, qz
        msg.poses.append(pose)
    return msg


def main():
    rospy.init_node('sim_robot')
    SimRobotNode().spin()
