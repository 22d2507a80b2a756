"""ROS edge of the clock a node's watchdogs time the robot's silence on
(doc/clock.md)."""
import time

import rospy

#: Wall s a node waits for its own clock thread to take in a /clock the
#: simulator already sent (it is merely descheduled: tens of ms at a load of
#: four processes per core); past it the node goes on with the clock it has.
CATCH_UP_BOUND_S = 0.5


def silence_clock():
    """With ``/use_sim_time`` (a simulated robot): simulated time, which
    the simulator advances in lockstep with the stack, so a descheduled
    node is late, never silent; it reads 0 until the node's first /clock,
    when no arrival can be timed. Else (a real robot) the wall clock."""
    if rospy.get_param('/use_sim_time', False):
        return rospy.get_time
    return time.monotonic


def catch_up(until_s, bound_s=CATCH_UP_BOUND_S):
    """Simulated time: wait until this node's clock reads ``until_s`` (s), at
    most ``bound_s`` wall s; return the clock. A /clock and a topic arrive on
    separate threads, so a message the simulator sent after a /clock can be
    handled before the node's clock moved."""
    cond = rospy.rostime.get_rostime_cond()
    end = time.monotonic() + bound_s
    with cond:
        while rospy.get_time() < until_s:
            left = end - time.monotonic()
            if left <= 0:
                break
            cond.wait(left)
    return rospy.get_time()
