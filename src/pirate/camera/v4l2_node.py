"""ROS edge of a real camera: a V4L2 device (the lab's frame grabber or a
USB camera) read with OpenCV, published as the twin's cameras are.

Private params: ``~camera`` ('front' or 'rear': the topics under
pirate.names.CAMERA_NAMESPACES and the optical frame the images are stamped
in), ``~device`` (a path such as /dev/video0, or an index), ``~width``,
``~height`` (pixels asked of the device), ``~rate`` (images per second),
``~fovy_deg`` (vertical field of view for CameraInfo: an ideal pinhole until
the camera is calibrated). Frames are grabbed all the time (a device's
buffer stays fresh) and published while someone subscribes. A device that
cannot be opened ends the node with its reason (exit 1).
"""
import rospy
from sensor_msgs.msg import CameraInfo, Image

from pirate import names
from pirate.camera import images_ros as images


def open_device(device, width, height):
    """An opened cv2.VideoCapture, or SystemExit with the reason."""
    try:
        import cv2
    except ImportError:
        rospy.logfatal('camera: OpenCV for Python is missing (Debian: python3-opencv)')
        raise SystemExit(1)
    capture = cv2.VideoCapture(int(device) if str(device).isdigit() else device, cv2.CAP_V4L2)
    if not capture.isOpened():
        rospy.logfatal('camera: cannot open V4L2 device %r', device)
        raise SystemExit(1)
    capture.set(cv2.CAP_PROP_FRAME_WIDTH, width)
    capture.set(cv2.CAP_PROP_FRAME_HEIGHT, height)
    return capture


def main():
    rospy.init_node('camera')
    camera = rospy.get_param('~camera', 'front')
    if camera not in names.CAMERA_NAMESPACES:
        rospy.logfatal('camera: ~camera %r is not one of %s', camera, ', '.join(sorted(names.CAMERA_NAMESPACES)))
        raise SystemExit(1)
    device = rospy.get_param('~device', '/dev/video0')
    capture = open_device(device, int(rospy.get_param('~width', 640)), int(rospy.get_param('~height', 480)))
    namespace, frame = names.CAMERA_NAMESPACES[camera], names.CAMERA_FRAMES[camera]
    image_pub = rospy.Publisher(namespace + '/image_raw', Image, queue_size=2)
    info_pub = rospy.Publisher(namespace + '/camera_info', CameraInfo, queue_size=2)
    fovy = float(rospy.get_param('~fovy_deg', 90.0))
    rate = rospy.Rate(float(rospy.get_param('~rate', 10.0)))
    rospy.loginfo('camera: %s camera from %s', camera, device)
    while not rospy.is_shutdown():
        grabbed, bgr = capture.read()
        if not grabbed:
            rospy.logwarn_throttle(5.0, 'camera: no frame from %s' % device)
        elif image_pub.get_num_connections() or info_pub.get_num_connections():
            stamp = rospy.Time.now()
            image_pub.publish(images.image(bgr, frame, stamp, encoding='bgr8'))
            info_pub.publish(images.camera_info(bgr.shape[1], bgr.shape[0], fovy, frame, stamp))
        rate.sleep()
    capture.release()
