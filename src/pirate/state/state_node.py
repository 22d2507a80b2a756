"""ROS edge of Pirate State (report 4.8, 5.11).

Subscribes the per-board Small State and the arrays sent to the robot (the
camera pan has no encoder: its angle is rebuilt from them), and at the end of every Mega refresh
cycle publishes pirate/RobotState (for event-driven guards),
sensor_msgs/JointState (RViz) and sensor_msgs/Imu (orientation). Serves the
joint-sensors and IMU blackboards. A 10 Hz check republishes the state
marked ``stale`` when the robot stops reporting, so nobody mistakes old
angles for fresh ones; silence is timed on the wall clock, or for a
simulated robot on simulated time, in lockstep with the stack (doc/clock.md).
"""
import math
import threading

import diagnostic_updater
import rospy
from sensor_msgs.msg import Imu, JointState

from pirate import health, names
from pirate.robot import safety, tables
from pirate.msg import ControlArray, RobotState, SetpointArray, SmallState
from pirate.srv import ImuSensor, ImuSensorResponse, JointSensors, JointSensorsResponse
from pirate.state.assembler import CYCLE_S, BadState, StateAssembler, stale_reason
from pirate.state.clock_ros import CATCH_UP_BOUND_S, catch_up, silence_clock


def roll_quaternion(orientation):
    """Quaternion (x, y, z, w) of the rear part for a Fig 4.7 orientation.

    ROS body frame: x forward, z up. Upright (pi/2) is the identity; lying on
    its right side (0) is a +pi/2 turn about x (the top points to -y).
    """
    half = (math.pi / 2 - orientation) / 2.0
    return math.sin(half), 0.0, 0.0, math.cos(half)


class PirateStateNode(object):
    """Small State in, state topics and blackboard services out."""

    def __init__(self):
        self.assembler = StateAssembler(rospy.get_param('~stale_after', 0.3))
        self._clock = silence_clock()
        self._sim_time = rospy.get_param('/use_sim_time', False)
        self._cycle_end_s = None        # simulated time of the cycle last ended at its last board
        self._lock = threading.Lock()
        self._logged = set()
        self._was_stale = False
        self._state_pub = rospy.Publisher(names.ROBOT_STATE_TOPIC, RobotState, queue_size=10)
        self._joint_pub = rospy.Publisher(names.JOINT_STATES_TOPIC, JointState, queue_size=10)
        self._imu_pub = rospy.Publisher(names.IMU_TOPIC, Imu, queue_size=10)
        rospy.Service(names.JOINT_SENSORS_SERVICE, JointSensors, self._joint_sensors)
        rospy.Service(names.IMU_SENSOR_SERVICE, ImuSensor, self._imu_sensor)
        rospy.Subscriber(names.SMALL_STATE_TOPIC, SmallState, self._on_small_state, queue_size=50)
        self._sent = [[0] * tables.SETPOINT_SIZE, [safety.MODE_CODES['pwm']] * tables.CONTROL_SIZE]
        rospy.Subscriber(names.SETPOINT_TOPIC, SetpointArray, self._on_sent, 0, queue_size=10)
        rospy.Subscriber(names.CONTROL_TOPIC, ControlArray, self._on_sent, 1, queue_size=10)
        rospy.Timer(rospy.Duration(0.1), self._check_stale)
        updater = diagnostic_updater.Updater()
        updater.setHardwareID('pirate')
        updater.add('Small State', self._diagnose)
        rospy.Timer(rospy.Duration(1.0), lambda _event: updater.update())

    def _diagnose(self, stat):
        """diagnostic_updater task: every board fresh, or which are silent; each board's loss rate."""
        snap = self._snapshot()
        with self._lock:
            loss = self.assembler.loss()
        return health.fill(stat, health.small_states(snap.stale, stale_reason(snap.silent, snap.age), snap.age,
                                                     len(tables.BOARDS), loss))

    def _snapshot(self):
        with self._lock:
            return self.assembler.snapshot(self._clock())

    def _on_small_state(self, msg):
        now = self._arrival()
        if not now:     # simulated time before this node's first /clock: no arrival time to judge silence by
            return
        try:
            with self._lock:
                complete = self.assembler.update(msg.board, msg.data, now)
            if complete and self._sim_time and msg.board == tables.BOARDS[-1]:
                self._cycle_end_s = now
        except BadState as bad:
            if str(bad) not in self._logged:
                self._logged.add(str(bad))
                rospy.logwarn('pirate_state: %s', bad)
            return
        if complete:
            snap = self._snapshot()
            if snap.stale and not self._was_stale:
                rospy.logwarn('pirate_state: %s; state is stale', stale_reason(snap.silent, snap.age))
            self._was_stale = snap.stale
            self._publish(snap)

    def _arrival(self):
        """When a Small State arrived. Simulated time: the first of a cycle
        waits until this node's clock reached the cycle (more than half a
        Mega cycle after the last ended; the simulator sent that /clock
        first), so a state is stamped in its cycle's time, not a lagging
        clock's (measurements.md#lockstep-stamp-lag)."""
        if self._cycle_end_s is None:
            return self._clock()
        until_s, self._cycle_end_s = self._cycle_end_s + CYCLE_S / 2, None
        now = catch_up(until_s)
        if now < until_s:
            rospy.logwarn_throttle(10.0, 'pirate_state: /clock did not pass %.2f s within %.1f s of a new cycle '
                                   '(it reads %.2f s): stamped with it', until_s, CATCH_UP_BOUND_S, now)
        return now

    def _on_sent(self, msg, which):
        """An array sent to the robot: the camera pan (no encoder) moves by it."""
        with self._lock:
            self._sent[which] = list(msg.data)
            self.assembler.command(self._sent[0], self._sent[1], self._clock())

    def _check_stale(self, _event):
        snap = self._snapshot()
        if snap.stale and snap.age != float('inf'):
            if not self._was_stale:
                rospy.logwarn('pirate_state: %s; state is stale', stale_reason(snap.silent, snap.age))
            self._publish(snap)
        self._was_stale = snap.stale

    def _publish(self, snap):
        now = rospy.Time.now()
        state = RobotState(name=snap.name, position=snap.position, effort=snap.effort,
                           orientation=snap.orientation, odometry=snap.odometry,
                           odometry_front=snap.part_odometry['front'], odometry_rear=snap.part_odometry['rear'],
                           velocity=snap.velocity, stale=snap.stale, silent_boards=list(snap.silent),
                           missed_boards=list(snap.missed))
        state.header.stamp = now
        self._state_pub.publish(state)
        joints = JointState(name=snap.name, position=snap.position, effort=snap.effort)
        joints.header.stamp = now
        self._joint_pub.publish(joints)
        imu = Imu()
        imu.header.stamp = now
        imu.header.frame_id = 'rear_part'
        q = roll_quaternion(snap.orientation)
        imu.orientation.x, imu.orientation.y, imu.orientation.z, imu.orientation.w = q
        self._imu_pub.publish(imu)

    def _joint_sensors(self, _req):
        snap = self._snapshot()
        return JointSensorsResponse(name=snap.name, position=snap.position, effort=snap.effort,
                                    odometry=snap.odometry, stale=snap.stale, age=snap.age)

    def _imu_sensor(self, _req):
        snap = self._snapshot()
        return ImuSensorResponse(roll=snap.orientation, pitch=0.0, yaw=0.0,
                                 stale=snap.stale, age=snap.age)


def main():
    rospy.init_node('pirate_state')
    PirateStateNode()
    rospy.spin()
