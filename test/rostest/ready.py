"""Shared by the rostests that send goals: wait until the stack can take one."""
import time

import rospy

from pirate import names
from pirate.srv import ServerStatus


def wait_robot_connected(timeout_s=60.0):
    """Block until the Pirate Server reports a fresh robot state; AssertionError if not."""
    status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
    status.wait_for_service(timeout_s)
    deadline = time.monotonic() + timeout_s
    while not status().robot_connected:
        if time.monotonic() > deadline:
            raise AssertionError('the Pirate Server saw no robot state within %.0f s' % timeout_s)
        time.sleep(0.1)   # poll the status service
