"""``run_mission --route MAP FROM TO [...]``: a route as a mission goal.

The client side of the mission executive (pirate.supervisory.executive_node):
plans the route locally first (a route the map cannot serve is refused
before anything is sent, exit 2; ``--check`` only prints the plan), then
sends it to ``/pirate/mission``, prints the executive's progress (each step,
what it waits for) and its log, and cancels the mission on Ctrl-C.
"""
import sys
import threading

import rospy
from actionlib_msgs.msg import GoalStatus

from pirate import names
from pirate.msg import MissionAction, MissionGoal
from pirate.supervisory import planner
from pirate.supervisory.goal_client_ros import SimpleGoalClient, wait_for_server
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

WAIT_FOR_SERVER_S = 30.0


def check_route(map_name, points, speed, home):
    """Plan the route here, so a bad one fails before anything is sent."""
    settings, max_drive_mm = load_settings()
    return planner.plan(network.load(network.world_path(map_name)), points, settings, max_drive_mm,
                        speed or None, home)


def run_route(args, out=print):
    """Check, then run the route of ``args`` (map, points, speed, level, check); an exit status."""
    try:
        route_plan = check_route(args.route[0], args.route[1:], args.speed, not args.no_home)
    except (network.WorldError, planner.PlanError) as refused:
        print('run_mission: %s' % refused, file=sys.stderr)
        return 2
    if args.check:
        out('\n'.join(planner.format_plan(route_plan)))
        return 0
    if args.level != 'manual':
        try:
            planner.check_runnable(route_plan)
        except planner.PlanError as refused:
            print('run_mission: %s' % refused, file=sys.stderr)
            return 2
    if not rospy.core.is_initialized():     # a caller's node (inspection_job) sends it as itself
        rospy.init_node('run_mission', anonymous=True)
    client = SimpleGoalClient(names.MISSION_ACTION, MissionAction)
    if not wait_for_server(client, WAIT_FOR_SERVER_S):
        print('run_mission: no mission executive at %s (roslaunch pirate mission_executive.launch)'
              % names.MISSION_ACTION, file=sys.stderr)
        return 2
    done = threading.Event()
    last = {'line': ''}

    def feedback(fb):
        line = 'step %d/%d %s at %.0f mm, %.0f s left%s' % (
            fb.step, fb.steps, fb.pab, fb.along_mm, fb.time_left_s,
            ', waiting for %s' % fb.waiting_for if fb.waiting_for else '')
        if line.split(' at ')[0] != last['line'].split(' at ')[0] or fb.waiting_for:
            out(line)
        last['line'] = line
    client.send_goal(MissionGoal(map=args.route[0], points=args.route[1:], speed=args.speed or 0.0,
                                 no_home=args.no_home, level=args.level),
                     done_cb=lambda *_: done.set(), feedback_cb=feedback)
    while not done.wait(0.2):       # wall poll so Ctrl-C (shutdown) is seen
        if rospy.is_shutdown():
            client.cancel_goal()
            print('run_mission: stopped; mission cancelled', file=sys.stderr)
            return 1
    result = client.get_result()
    for line in (result.log if result else []):
        out('  %s' % line)
    out('mission %s: %s' % (result.status if result else 'ended', result.message if result else ''))
    return 0 if client.get_state() == GoalStatus.SUCCEEDED and result.status == 'succeeded' else 1
