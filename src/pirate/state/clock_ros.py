"""ROS edge of the clock a node's watchdogs time the robot's silence on
(doc/clock.md)."""
import time

import rospy


def silence_clock():
    """With ``/use_sim_time`` (a simulated robot): simulated time, which
    the simulator advances in lockstep with the stack, so a descheduled
    node is late, never silent; it reads 0 until the node's first /clock,
    when no arrival can be timed. Else (a real robot) the wall clock."""
    if rospy.get_param('/use_sim_time', False):
        return rospy.get_time
    return time.monotonic
