"""The pirate_viz node: the robot's roll in the pipe, and the pipe, for RViz.

Reads only what the Pirate State node publishes (/pirate/state) and the
Pirate Server's goals, so it works the same with the simulated and the real
robot. robot_state_publisher turns /joint_states into the joints' TF; this
node adds the one transform it cannot know, pipe -> base_link, rolled by the
IMU orientation (report 7.2 asks the visualisation to show it), and a
translucent cylinder for the pipe.

Parameters (private):
  ~pipe_diameter  mm, the pipe drawn until a goal names one (default 90)
  ~pipe_length    m, length of the drawn pipe (default 1.2)
  ~pipe_frame     fixed frame of the pipe (default 'pipe')
  ~base_frame     the URDF's base link (default 'base_link')
Publishes ~pipe_marker (visualization_msgs/Marker) once a second and TF.
"""
import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped
from visualization_msgs.msg import Marker

from pirate import names
from pirate.msg import PirateActionGoal, RobotState
from pirate.viz import pose

PIPE_RGBA = (0.55, 0.7, 0.85, 0.25)   # translucent steel blue
MARKER_PERIOD_S = 1.0


class PirateViz(object):
    """Broadcasts pipe -> base_link and draws the pipe."""

    def __init__(self):
        self.pipe_diameter = float(rospy.get_param('~pipe_diameter', 90.0))
        self.pipe_length = float(rospy.get_param('~pipe_length', 1.2))
        self.pipe_frame = rospy.get_param('~pipe_frame', 'pipe')
        self.base_frame = rospy.get_param('~base_frame', 'base_link')
        pose.base_in_pipe(0.0, self.pipe_diameter)   # ValueError at start-up if bad
        self.broadcaster = tf2_ros.TransformBroadcaster()
        self.marker_pub = rospy.Publisher('~pipe_marker', Marker, queue_size=1, latch=True)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self.on_state, queue_size=10)
        rospy.Subscriber(names.PIRATE_ACTION + '/goal', PirateActionGoal, self.on_goal)
        rospy.Timer(rospy.Duration(MARKER_PERIOD_S), lambda _event: self.publish_marker())
        self.publish_marker()

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
        self.publish_marker()

    def on_state(self, msg):
        """Roll the base frame by the measured orientation."""
        try:
            xyz, quat = pose.base_in_pipe(msg.orientation, self.pipe_diameter)
        except ValueError as error:
            rospy.logerr_once('pirate_viz: state ignored, last pose kept: %s' % error)
            return
        tf = TransformStamped()
        tf.header.stamp = msg.header.stamp if not msg.header.stamp.is_zero() else rospy.Time.now()
        tf.header.frame_id = self.pipe_frame
        tf.child_frame_id = self.base_frame
        (tf.transform.translation.x, tf.transform.translation.y,
         tf.transform.translation.z) = xyz
        (tf.transform.rotation.x, tf.transform.rotation.y,
         tf.transform.rotation.z, tf.transform.rotation.w) = quat
        self.broadcaster.sendTransform(tf)

    def publish_marker(self):
        marker = Marker()
        marker.header.frame_id = self.pipe_frame
        marker.header.stamp = rospy.Time(0)   # "latest": the pipe never moves
        marker.ns = 'pipe'
        marker.id = 0
        marker.type = Marker.CYLINDER
        marker.action = Marker.ADD
        # A cylinder marker's axis is its z; turn it onto the pipe's x.
        (marker.pose.orientation.x, marker.pose.orientation.y,
         marker.pose.orientation.z, marker.pose.orientation.w) = pose.cylinder_along_x()
        marker.scale.x = marker.scale.y = self.pipe_diameter / 1000.0
        marker.scale.z = self.pipe_length
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = PIPE_RGBA
        self.marker_pub.publish(marker)


def main():
    rospy.init_node('pirate_viz')
    try:
        PirateViz()
    except ValueError as error:
        rospy.logfatal('pirate_viz: %s' % error)
        raise SystemExit(1)
    rospy.spin()
