"""sensor_msgs/Image and CameraInfo of a camera, and when to publish them.

No rospy node here: :class:`CameraStreams` takes its publishers and a
render function, so tests drive it without a ROS master. An image is
published only while someone subscribes to it or to its camera info.
"""
import math

from sensor_msgs.msg import CameraInfo, Image

from pirate import names


def camera_info(width, height, fovy_deg, frame_id, stamp):
    """CameraInfo of an ideal pinhole (no distortion) with vertical field of
    view ``fovy_deg``, square pixels, the centre in the image's middle."""
    focal = height / 2.0 / math.tan(math.radians(fovy_deg) / 2.0)
    cx, cy = (width - 1) / 2.0, (height - 1) / 2.0
    info = CameraInfo(width=width, height=height, distortion_model='plumb_bob', D=[0.0] * 5,
                      K=[focal, 0.0, cx, 0.0, focal, cy, 0.0, 0.0, 1.0],
                      R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
                      P=[focal, 0.0, cx, 0.0, 0.0, focal, cy, 0.0, 0.0, 0.0, 1.0, 0.0])
    info.header.frame_id, info.header.stamp = frame_id, stamp
    return info


def image(pixels, frame_id, stamp, encoding='rgb8'):
    """Image of a (height, width, 3) uint8 array, rows top first."""
    height, width = pixels.shape[:2]
    msg = Image(height=height, width=width, encoding=encoding, is_bigendian=0, step=width * 3,
                data=pixels.tobytes())
    msg.header.frame_id, msg.header.stamp = frame_id, stamp
    return msg


class CameraStreams(object):
    """Publishes each camera every ``period_s`` of the caller's clock while
    it has a subscriber. ``publishers``: camera -> (image publisher, info
    publisher), anything with ``publish`` and ``get_num_connections``;
    ``render(camera)`` returns the pixels (called only when an image is due)."""

    def __init__(self, publishers, render, period_s, fovy_deg):
        self.publishers, self.render = publishers, render
        self.period_s, self.fovy_deg = period_s, fovy_deg
        self._due = {camera: 0.0 for camera in publishers}

    def watched(self, camera):
        """True while someone subscribes to the camera's image or its info."""
        return any(pub.get_num_connections() > 0 for pub in self.publishers[camera])

    def tick(self, now_s, stamp):
        """Publish every watched camera whose next image is due at ``now_s``
        (seconds of the robot's clock), stamped ``stamp``; return the cameras published."""
        published = []
        for camera, (image_pub, info_pub) in sorted(self.publishers.items()):
            if now_s + 1e-9 < self._due[camera] or not self.watched(camera):
                continue
            self._due[camera] = now_s + self.period_s
            pixels = self.render(camera)
            frame = names.CAMERA_FRAMES[camera]
            image_pub.publish(image(pixels, frame, stamp))
            info_pub.publish(camera_info(pixels.shape[1], pixels.shape[0], self.fovy_deg, frame, stamp))
            published.append(camera)
        return published
