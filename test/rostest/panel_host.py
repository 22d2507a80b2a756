#!/usr/bin/env python3
"""Stand-in manager for panel tests and the Stop-latency bench: the shared
Setpoint / Control / Limit objects plus MapperRos, composed the way the
pirate_manager node composes them, with a PAB client that has no server
(every goal refused). Used by bench/mapper_stop_latency when no
pirate_manager is installed, and to try the panel scenarios that need no
Pirate Server."""
import rospy

from pirate import commands, names
from pirate.msg import ControlArray, LimitArray, SetpointArray
from pirate.panel.mapper_ros import MapperRos


class NoServer(object):
    def send_goal(self, name, pipe_diameter, option):
        return False, 'no Pirate Server in this stand-in'

    def cancel(self):
        pass

    def is_active(self):
        return False


def main():
    rospy.init_node('pirate_manager')
    log = rospy.logwarn
    control = commands.Control(rospy.Publisher(names.CONTROL_TOPIC, ControlArray, queue_size=10),
                               lambda v: ControlArray(data=v), log=log)
    setpoint = commands.Setpoint(rospy.Publisher(names.SETPOINT_TOPIC, SetpointArray, queue_size=10),
                                 lambda v: SetpointArray(data=v), control, log=log)
    limit = commands.Limit(rospy.Publisher(names.LIMITS_TOPIC, LimitArray, queue_size=10),
                           lambda v: LimitArray(data=v), log=log)
    MapperRos(setpoint, control, limit, NoServer())
    rospy.spin()


if __name__ == '__main__':
    main()
