"""ROS edge of :mod:`pirate.state.robot_clock`: the clock a node's watchdogs
time the robot's silence on."""
import time

import rospy

from pirate.state.robot_clock import RobotClock

TICK_S = 0.05       # sim s between ticks: 0.05 s of wall time at x1, well inside the slack


def silence_clock():
    """With ``/use_sim_time`` (a simulated robot): a :class:`RobotClock`
    ticked by a timer on simulated time, so it stands still when the
    simulator does. Else (a real robot) the wall clock."""
    if not rospy.get_param('/use_sim_time', False):
        return time.monotonic
    clock = RobotClock()
    rospy.Timer(rospy.Duration(TICK_S), lambda _event: clock.tick())
    return clock
