#!/usr/bin/env python3
"""A goal's owner for fault_owner_lost: sends one long Drive and lives until killed.

Run by the test as a process of its own (node ``/goal_owner``), which the
test then SIGKILLs mid-drive: as a mission executive dies.
"""
import rospy

from pirate import names
from pirate.msg import PirateAction, PirateGoal
from pirate.supervisory.goal_client_ros import SimpleGoalClient, wait_for_server

DRIVE_MM, SPEED_MM_S = 2000.0, 100.0     # 20 s of robot time: it is killed long before the end

if __name__ == '__main__':
    rospy.init_node('goal_owner')
    client = SimpleGoalClient(names.PIRATE_ACTION, PirateAction)
    if not wait_for_server(client, 60.0):       # wall s: the simulated clock may not run yet
        raise SystemExit('the Pirate Server never came')
    client.send_goal(PirateGoal(name=PirateGoal.DRIVE, pipe_diameter=90, distance=DRIVE_MM, speed=SPEED_MM_S))
    rospy.spin()
