"""ROS edge of the mission runner: an actionlib client of the Pirate Server.

Usage: ``rosrun pirate run_mission [--check] [MISSION.yaml]`` (default: the
report's test mission), or ``rosrun pirate run_mission --route MAP FROM TO
[...]`` for a route over a pipe map, run by the mission executive
(pirate.supervisory.route_client_ros). The mission is checked completely first (every
error with its line; exit 2); ``--check`` prints the plan and exits
without a ROS master. Exits 0 when every step succeeded, 1 otherwise.
Each goal is sent and waited for by pirate.supervisory.goal_client_ros.
"""
import argparse
import os
import sys
import time

import actionlib
import rospy

from pirate import names, paths
from pirate.sequencer.guards import load_files
from pirate.supervisory import route_client_ros
from pirate.supervisory.goal_client_ros import GoalClient, wait_for_server
from pirate.supervisory.mission import MissionError, MissionRunner, TracedPrimitive, load_mission, plan
from pirate.msg import PirateAction, PirateGoal
from pirate.srv import ServerStatus

def default_mission():
    """The report's test mission shipped in config/missions/."""
    return os.path.join(paths.CONFIG_DIR, 'missions', 'report_test_mission.yaml')


class ActionGoalRunner(object):
    """Sends one step as a goal and waits for its terminal state."""

    def __init__(self, timeout_s):
        self._client = actionlib.ActionClient(names.PIRATE_ACTION, PirateAction)
        self._timeout = timeout_s
        self._goals = GoalClient(self._client, timeout_s, rospy.get_time, rospy.is_shutdown)

    def connect(self, wall_timeout=30.0):
        """Wait for the Pirate Server and for it to see the robot; the reason if not."""
        if not wait_for_server(self._client, wall_timeout):
            return 'no Pirate Server at %s' % names.PIRATE_ACTION
        status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
        deadline = time.monotonic() + wall_timeout
        while time.monotonic() < deadline and not rospy.is_shutdown():
            try:
                status.wait_for_service(max(deadline - time.monotonic(), 0.1))
                if status().robot_connected:
                    return None
            except (rospy.ROSException, rospy.ServiceException):
                pass
            time.sleep(0.1)   # poll the status service
        return 'the Pirate Server sees no robot state within %.0f s' % wall_timeout

    def __call__(self, step):
        """(status, message, primitive trace) of ``step`` sent as a goal."""
        goal = PirateGoal(name=step.code, pipe_diameter=step.pipe_diameter, distance=step.distance,
                          speed=step.speed, option=step.option)
        ending = self._goals.run(goal)
        result = ending.result
        trace = [TracedPrimitive(p.name, p.guard, p.start, p.end, p.outcome)
                 for p in (result.primitives if result else [])]
        message = ending.message
        if result and result.server_state:
            message += ' [%s]' % result.server_state
        return ending.status, message, trace


def _check(path):
    """The checked mission and the default drive speed; MissionError/IOError if bad."""
    tables, common = load_files()
    mission = load_mission(path, sorted(tables), common['drive'])
    return mission, common['drive']['default_speed']


def main(argv=None):
    parser = argparse.ArgumentParser(description='Run a PIRATE mission (a list of PAB goals).')
    parser.add_argument('mission', nargs='?', help='mission YAML (default: the report test mission)')
    parser.add_argument('--timeout', type=float, default=300.0, help='per goal, s of robot time')
    parser.add_argument('--check', action='store_true',
                        help='check the mission and print the plan; no ROS, nothing moves')
    parser.add_argument('--route', nargs='+', metavar='MAP FROM TO',
                        help='a route over a pipe map (world file or name; point names, in order), '
                             'run by the mission executive')
    parser.add_argument('--speed', type=float, default=0.0, help='--route: mm/s (0: config/supervisory.yaml)')
    parser.add_argument('--level', default='full', choices=('full', 'confirm', 'manual'),
                        help='--route: autonomy level')
    parser.add_argument('--no-home', action='store_true', help='--route: end clamped, do not home')
    args = parser.parse_args(rospy.myargv(argv or sys.argv)[1:])
    if args.route:
        if args.mission or len(args.route) < 3:
            parser.error('--route takes MAP FROM TO [...] and no mission file')
        return route_client_ros.run_route(args)
    path = args.mission or default_mission()
    try:
        mission, default_speed = _check(path)
    except (MissionError, IOError) as error:
        print('run_mission: %s:\n%s' % (path, error), file=sys.stderr)
        return 2
    if args.check:
        print('\n'.join(plan(mission, default_speed)))
        return 0
    rospy.init_node('run_mission', anonymous=True)
    runner = ActionGoalRunner(args.timeout)
    problem = runner.connect()
    if problem:
        print('run_mission: %s' % problem, file=sys.stderr)
        return 2
    clocks = lambda: (rospy.get_time(), time.monotonic())  # noqa: E731
    results = MissionRunner(runner, clocks, out=lambda line: print(line, flush=True)).run(mission)
    ok = len(results) == len(mission.steps) and all(r.status == 'succeeded' for r in results)
    return 0 if ok else 1
