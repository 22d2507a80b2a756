"""The pirate_viz node: the robot's roll in the pipe and where it is along it, for RViz.

Reads only what the robot senses - the Pirate State node's /pirate/state,
the Pirate Server's goals and, while a mission runs, its estimate along the
map - so it works the same with the simulated and the real robot.
robot_state_publisher turns /joint_states into the joints' TF; this node
adds the one transform it cannot know, pipe -> base_link, rolled by the IMU
orientation (report 7.2 asks the visualisation to show it) and moved along
the pipe's axis by the odometry, a translucent stretch of pipe following
the robot, its ring marks and metre labels, and the odometry (and the
mission's estimate) as text beside the robot (pirate.viz.along_pipe).

Parameters (private):
  ~pipe_diameter  mm, the pipe drawn until a goal names one (default 90)
  ~pipe_length    m, length of the drawn stretch of pipe (default 2.0: a metre label always on it)
  ~pipe_frame     fixed frame of the pipe (default 'pipe')
  ~base_frame     the URDF's base link (default 'base_link')
Publishes TF, ~pipe_marker (visualization_msgs/Marker) and ~position_markers
(visualization_msgs/MarkerArray: rings, labels, text), 5 times a second.
"""
import rospy
import tf2_ros
from geometry_msgs.msg import Point, TransformStamped
from std_msgs.msg import Float64
from visualization_msgs.msg import Marker, MarkerArray

from pirate import names
from pirate.msg import PirateActionGoal, RobotState
from pirate.viz import along_pipe, pose

PIPE_RGBA = (0.55, 0.7, 0.85, 0.25)   # translucent steel blue
RING_RGBA = (0.8, 0.9, 1.0, 0.8)
TEXT_RGBA = (1.0, 1.0, 1.0, 1.0)
RING_WIDTH_M = 0.002
LABEL_HEIGHT_M = 0.03      # metre labels under the pipe, clear of the text above it
TEXT_HEIGHT_M = 0.035
TEXT_ABOVE_PIPE_M = 0.06   # the text's middle, above the pipe's top
MARKER_PERIOD_S = 0.2      # the text keeps up with a driving robot


class PirateViz(object):
    """Broadcasts pipe -> base_link and draws the pipe."""

    def __init__(self):
        self.pipe_diameter = float(rospy.get_param('~pipe_diameter', 90.0))
        self.pipe_length = float(rospy.get_param('~pipe_length', 2.0))
        self.pipe_frame = rospy.get_param('~pipe_frame', 'pipe')
        self.base_frame = rospy.get_param('~base_frame', 'base_link')
        pose.base_in_pipe(0.0, self.pipe_diameter)   # ValueError at start-up if bad
        self.odometry_mm = 0.0
        self.estimate = along_pipe.MissionEstimate()
        self.broadcaster = tf2_ros.TransformBroadcaster()
        self.marker_pub = rospy.Publisher('~pipe_marker', Marker, queue_size=1, latch=True)
        self.position_pub = rospy.Publisher('~position_markers', MarkerArray, queue_size=1, latch=True)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self.on_state, queue_size=10)
        rospy.Subscriber(names.PIRATE_ACTION + '/goal', PirateActionGoal, self.on_goal)
        rospy.Subscriber(names.MISSION_ALONG_TOPIC, Float64, lambda msg: self.estimate.heard_along(
            msg.data, rospy.get_time()), queue_size=1)
        rospy.Subscriber(names.MISSION_UNCERTAINTY_TOPIC, Float64, lambda msg: self.estimate.heard_uncertainty(
            msg.data, rospy.get_time()), queue_size=1)
        rospy.Timer(rospy.Duration(MARKER_PERIOD_S), lambda _event: self.publish_markers())
        self.publish_markers()

    def on_goal(self, msg):
        """Draw the pipe a goal names (goals without a diameter carry 0)."""
        diameter = msg.goal.pipe_diameter
        if diameter == 0 or diameter == self.pipe_diameter:
            return
        try:
            pose.base_in_pipe(0.0, diameter)
        except ValueError as error:
            rospy.logerr_once('pirate_viz: goal pipe ignored: %s' % error)
            return
        self.pipe_diameter = float(diameter)
        self.publish_markers()

    def on_state(self, msg):
        """Roll the base frame by the measured orientation, move it by the odometry."""
        try:
            xyz, quat = pose.base_in_pipe(msg.orientation, self.pipe_diameter)
            along_m = along_pipe.base_along_m(msg.odometry)
        except ValueError as error:
            rospy.logerr_once('pirate_viz: state ignored, last pose kept: %s' % error)
            return
        tf = TransformStamped()
        tf.header.stamp = msg.header.stamp if not msg.header.stamp.is_zero() else rospy.Time.now()
        tf.header.frame_id = self.pipe_frame
        tf.child_frame_id = self.base_frame
        self.odometry_mm = msg.odometry
        tf.transform.translation.x = along_m
        tf.transform.translation.y, tf.transform.translation.z = xyz[1:]
        (tf.transform.rotation.x, tf.transform.rotation.y,
         tf.transform.rotation.z, tf.transform.rotation.w) = quat
        self.broadcaster.sendTransform(tf)

    def publish_markers(self):
        self.marker_pub.publish(self.pipe_marker())
        self.position_pub.publish(MarkerArray(markers=self.position_markers()))

    def _marker(self, ns, marker_id, marker_type, rgba):
        marker = Marker()
        marker.header.frame_id = self.pipe_frame
        marker.header.stamp = rospy.Time(0)   # "latest": drawn in the fixed pipe frame
        marker.ns = ns
        marker.id = marker_id
        marker.type = marker_type
        marker.action = Marker.ADD
        marker.pose.orientation.w = 1.0
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = rgba
        return marker

    def pipe_marker(self):
        """The stretch of pipe around the robot."""
        marker = self._marker('pipe', 0, Marker.CYLINDER, PIPE_RGBA)
        marker.pose.position.x = along_pipe.stretch_centre_mm(self.odometry_mm) / 1000.0
        # A cylinder marker's axis is its z; turn it onto the pipe's x.
        (marker.pose.orientation.x, marker.pose.orientation.y,
         marker.pose.orientation.z, marker.pose.orientation.w) = pose.cylinder_along_x()
        marker.scale.x = marker.scale.y = self.pipe_diameter / 1000.0
        marker.scale.z = self.pipe_length
        return marker

    def position_markers(self):
        """The stretch's rings and metre labels, and the text beside the robot."""
        radius = self.pipe_diameter / 2000.0
        marks = along_pipe.ring_marks_mm(along_pipe.stretch_centre_mm(self.odometry_mm),
                                         self.pipe_length * 1000.0)
        rings = self._marker('rings', 0, Marker.LINE_LIST, RING_RGBA)
        rings.scale.x = RING_WIDTH_M
        rings.points = [Point(*end) for x in marks
                        for segment in along_pipe.ring_segments(x / 1000.0, radius) for end in segment]
        markers = [rings]
        labels = along_pipe.metre_labels(marks)
        for index, (x, text) in enumerate(labels):
            label = self._marker('metre labels', index, Marker.TEXT_VIEW_FACING, RING_RGBA)
            label.pose.position.x, label.pose.position.z = x / 1000.0, -radius - LABEL_HEIGHT_M
            label.scale.z = LABEL_HEIGHT_M
            label.text = text
            markers.append(label)
        # A stretch holds one label per metre of its length, plus one: delete the slots left over.
        for index in range(len(labels), int(self.pipe_length) + 2):
            gone = self._marker('metre labels', index, Marker.TEXT_VIEW_FACING, RING_RGBA)
            gone.action = Marker.DELETE
            markers.append(gone)
        text = self._marker('position', 0, Marker.TEXT_VIEW_FACING, TEXT_RGBA)
        text.pose.position.x = along_pipe.base_along_m(self.odometry_mm)
        text.pose.position.z = radius + TEXT_ABOVE_PIPE_M
        text.scale.z = TEXT_HEIGHT_M
        text.text = along_pipe.position_text(self.odometry_mm, *self.estimate.current(rospy.get_time()))
        markers.append(text)
        return markers


def main():
    rospy.init_node('pirate_viz')
    try:
        PirateViz()
    except ValueError as error:
        rospy.logfatal('pirate_viz: %s' % error)
        raise SystemExit(1)
    rospy.spin()
