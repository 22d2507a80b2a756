"""The world_viz node: the physics twin's pipe network and true robot, for RViz.

Publishes, in the fixed frame ``world``: ``~pipes`` (MarkerArray, latched)
the network of ``~world`` drawn translucent, its defects as red spheres,
and ``~robot`` (MarkerArray) the modules and wheels at their true poses from the ground-truth topic
(names.GROUND_TRUTH_TOPIC). Only for display: the real robot has no ground
truth, and no PAB reads it.

Private params: ``~world`` (file or name under config/worlds/).
"""
import rospy
import tf2_ros
from geometry_msgs.msg import PoseArray, TransformStamped
from visualization_msgs.msg import Marker, MarkerArray

from pirate import names
from pirate.sim import twin_model
from pirate.world.network import world_path
from pirate.viz import world_markers
from pirate.world import network

FRAME = names.MAP_FRAME
PIPE_RGBA = (0.55, 0.7, 0.85, 0.3)
MODULE_RGBA = (0.85, 0.45, 0.1, 1.0)        # the URDF's pirate orange
WHEEL_RGBA = (0.1, 0.1, 0.1, 1.0)
#: TRUTH_BODIES order (front to rear) -> world_markers.robot_shapes directions.
DIRECTIONS = (1, 1, 1, 2, -2, -1, -1, -1)
DEFECT_RGBA = (0.9, 0.1, 0.1, 0.9)
TYPES = {'cylinder': Marker.CYLINDER, 'wheel': Marker.CYLINDER, 'shell': Marker.CYLINDER, 'defect': Marker.SPHERE}


def to_markers(shapes, ns, colours):
    """A MarkerArray from world_markers shapes."""
    out = MarkerArray()
    for index, (kind, centre, quat, scale) in enumerate(shapes):
        marker = Marker(type=TYPES[kind], action=Marker.ADD, ns=ns, id=index)
        marker.header.frame_id = FRAME
        marker.pose.position.x, marker.pose.position.y, marker.pose.position.z = centre
        (marker.pose.orientation.x, marker.pose.orientation.y,
         marker.pose.orientation.z, marker.pose.orientation.w) = quat
        marker.scale.x, marker.scale.y, marker.scale.z = scale
        marker.color.r, marker.color.g, marker.color.b, marker.color.a = colours[kind]
        out.markers.append(marker)
    return out


class WorldViz(object):
    def __init__(self):
        self.world = network.load(world_path(rospy.get_param('~world', 'straight_90')))
        self.geometry = twin_model.load_config()['geometry']
        pipes = rospy.Publisher('~pipes', MarkerArray, queue_size=1, latch=True)
        self.robot_pub = rospy.Publisher('~robot', MarkerArray, queue_size=1)
        pipes.publish(to_markers(world_markers.pipe_shapes(self.world) + world_markers.defect_shapes(self.world),
                                 'pipes', {'cylinder': PIPE_RGBA, 'defect': DEFECT_RGBA}))
        rospy.Subscriber(names.GROUND_TRUTH_TOPIC, PoseArray, self.on_truth, queue_size=1)
        self._static = tf2_ros.StaticTransformBroadcaster()
        self._static.sendTransform(_identity(FRAME, FRAME + '_origin'))   # so RViz knows the frame

    def on_truth(self, msg):
        poses = [((p.position.x, p.position.y, p.position.z),
                  (p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)) for p in msg.poses]
        shapes = world_markers.robot_shapes(poses, DIRECTIONS, self.geometry)
        self.robot_pub.publish(to_markers(shapes, 'robot', {'shell': MODULE_RGBA, 'wheel': WHEEL_RGBA}))


def _identity(parent, child):
    tf = TransformStamped()
    tf.header.stamp = rospy.Time.now()
    tf.header.frame_id, tf.child_frame_id = parent, child
    tf.transform.rotation.w = 1.0
    return tf


def main():
    rospy.init_node('world_viz')
    try:
        WorldViz()
    except network.WorldError as error:
        rospy.logfatal('world_viz: %s' % error)
        raise SystemExit(1)
    rospy.spin()
