"""ROS edge of the mission runner: an actionlib client of the Pirate Server.

Usage: ``rosrun pirate run_mission [MISSION.yaml]`` (default: the report's
test mission). Exits 0 when every step succeeded, 1 otherwise.
"""
import argparse
import os
import sys
import time

import actionlib
import rospkg
import rospy
from actionlib_msgs.msg import GoalStatus

from pirate import names
from pirate.supervisory.mission import MissionError, MissionRunner, load_mission
from pirate.msg import PirateAction, PirateGoal
from pirate.srv import ServerStatus

STATUS = {GoalStatus.SUCCEEDED: 'succeeded', GoalStatus.ABORTED: 'aborted',
          GoalStatus.PREEMPTED: 'preempted', GoalStatus.REJECTED: 'rejected',
          GoalStatus.RECALLED: 'recalled'}


def default_mission():
    """The report's test mission shipped in config/missions/."""
    return os.path.join(rospkg.RosPack().get_path('pirate'), 'config', 'missions',
                        'report_test_mission.yaml')


class ActionGoalRunner(object):
    """Sends one step as a goal and waits for its terminal state."""

    def __init__(self, timeout_s):
        self._client = actionlib.SimpleActionClient(names.PIRATE_ACTION, PirateAction)
        self._timeout = timeout_s

    def connect(self, wall_timeout=30.0):
        """Wait for the Pirate Server and for it to see the robot; the reason if not."""
        if not self._client.wait_for_server(rospy.Duration(self._timeout)):
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

    def __call__(self, step, on_feedback):
        goal = PirateGoal(name=step.code, pipe_diameter=step.pipe_diameter, distance=step.distance,
                          speed=step.speed, option=step.option)
        self._client.send_goal(goal, feedback_cb=lambda fb: on_feedback(fb.primitive, fb.guard))
        if not self._client.wait_for_result(rospy.Duration(self._timeout)):
            self._client.cancel_goal()
            return 'timeout', 'no result within %.0f s; goal cancelled' % self._timeout
        result = self._client.get_result()
        return STATUS.get(self._client.get_state(), 'unknown'), result.message if result else ''


def main(argv=None):
    parser = argparse.ArgumentParser(description='Run a PIRATE mission (a list of PAB goals).')
    parser.add_argument('mission', nargs='?', help='mission YAML (default: the report test mission)')
    parser.add_argument('--timeout', type=float, default=300.0, help='per goal, s of robot time')
    args = parser.parse_args(rospy.myargv(argv or sys.argv)[1:])
    rospy.init_node('run_mission', anonymous=True)
    try:
        mission = load_mission(args.mission or default_mission())
    except (MissionError, IOError) as error:
        print('run_mission: %s' % error, file=sys.stderr)
        return 2
    runner = ActionGoalRunner(args.timeout)
    problem = runner.connect()
    if problem:
        print('run_mission: %s' % problem, file=sys.stderr)
        return 2
    clocks = lambda: (rospy.get_time(), time.monotonic())  # noqa: E731
    results = MissionRunner(runner, clocks, out=lambda line: print(line, flush=True)).run(mission)
    ok = len(results) == len(mission.steps) and all(r.status == 'succeeded' for r in results)
    return 0 if ok else 1
