"""mission_executive: the Supervisory layer's ROS edge.

An actionlib server, ``/pirate/mission`` (pirate/MissionAction): a goal
names a pipe map and the points to visit; the node plans the route
(pirate.supervisory.planner), refuses it at once with the reason if the map
cannot serve it, and otherwise runs it with the executive
(pirate.supervisory.executive) as a client of the Pirate Server. Any client
can start, watch (feedback: step k of n, position along the map, time left,
what it waits for) and cancel a mission. One mission at a time.

The operator's word during a mission: the ``/pirate/mission/command``
service (pirate/MissionCommand: pause, resume, confirm, cancel,
level full|confirm|manual), which the panel's mission buttons call; between
missions ``level X`` sets the level of the next mission whose goal names
none (the panel's level buttons work before a mission), and ``cancel``
cancels a mission sent before it that has not come yet (the panel's Stop
overtaking a goal on its way). The estimated position
is published as a pose on the map (``/pirate/mission/pose``, frame ``map``)
and as millimetres along the path (``/pirate/mission/along_mm``), with how
far it may be off (``/pirate/mission/uncertainty_mm``, the localiser's
bound), 5 Hz. The mission accepted last, with its map and points (a resumed
mission's too, whose goal names neither), is latched on
``/pirate/mission/current`` (pirate/MissionActionGoal), so a node started
late still learns it.

The executive's log is written as it goes (pirate.supervisory.mission_log,
``~log``, default ``$ROS_HOME/pirate/mission_log.jsonl``): at start-up the
node says how the last mission in it ended, or where it stood if the
executive died mid-mission; between missions the command ``last`` says it
again. A mission the executive died in is taken up from the log
(pirate.supervisory.resume) by a goal with ``resume`` set, which the command
``resume`` between missions sends (the panel's resume button): it runs as
any mission, its feedback and result on ``/pirate/mission``, from the first
step not known to have succeeded; a refusal says why.

Params (private): ``~goal_timeout`` (s of robot time one PAB may take
before the executive cancels it, default 600); ``~log`` (the log's path).
"""
import os
import threading

import actionlib
import rospkg
import rospy
import yaml
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import Point, PoseStamped
from std_msgs.msg import Float64
from visualization_msgs.msg import Marker, MarkerArray

from pirate import names
from pirate.msg import (MissionAction, MissionActionGoal, MissionFeedback, MissionGoal, MissionResult, PirateAction,
                        PirateGoal, RobotState)
from pirate.sequencer import goals
from pirate.sequencer.clamp_state import IDLE_CLAMPED
from pirate.srv import MissionCommand, MissionCommandResponse, ServerStatus
from pirate.supervisory import executive as ex
from pirate.supervisory import mission_log, planner
from pirate.supervisory.resume import CannotResume, take_up
from pirate.supervisory.goal_client_ros import GoalClient, wait_for_server
from pirate.supervisory.localiser import Localiser
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network
from pirate.world.pose import path_points, pose_along

POSE_PERIOD_S = 0.2
SERVER_WAIT_S = 2.0                     # wall s the command ``resume`` waits for the node's own action server
ROUTE_RGBA = (0.1, 0.8, 0.2, 0.9)        # the planned route, green
LINE_WIDTH_M = 0.008


class ActionRobot(object):
    """The executive's robot: one Pirate Server goal at a time
    (pirate.supervisory.goal_client_ros), its end as an :data:`ex.Report`."""

    def __init__(self, timeout_s):
        self.goals = GoalClient(actionlib.ActionClient(names.PIRATE_ACTION, PirateAction), timeout_s,
                                rospy.get_time, rospy.is_shutdown)
        self.odometry_mm = None
        self._status = rospy.ServiceProxy(names.SERVER_STATUS_SERVICE, ServerStatus)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=5)

    def _on_state(self, msg):
        if not msg.stale:
            self.odometry_mm = msg.odometry

    def run(self, step):
        """Send ``step`` as a goal and wait for its end: an :data:`ex.Report`."""
        option = goals.OPTIONS.get(step.option or 'NONE')
        if option is None:
            return ex.Report('rejected', 'option %s is not one of Pirate.action' % step.option,
                             self.odometry_mm, None, False)
        goal = PirateGoal(name=goals.CODES[step.pab], pipe_diameter=step.pipe_diameter,
                          distance=step.distance_mm, speed=step.speed_mm_s, option=option)
        start_mm = self.odometry_mm
        return report(self.goals.run(goal), self.odometry_mm, start_mm)

    def clamped(self):
        """The Pirate Server's sensed state now: Idle Clamped or not."""
        try:
            return self._status().server_state == IDLE_CLAMPED
        except rospy.ServiceException:
            return False        # unknown: re-clamping is the safe side

    def cancel(self):
        """Cancel the running goal (any thread)."""
        self.goals.cancel()


def report(ending, odometry_mm, start_odometry_mm):
    """The executive's :data:`ex.Report` of a goal's :data:`Ending`: a goal
    that ran out of time counts as aborted (the policy may retry it), one
    recalled before it started as rejected (a retry cannot help). The
    junction's place counts from ``start_odometry_mm``, the odometry when the
    goal was sent."""
    status = {'timeout': 'aborted', 'interrupted': 'aborted', 'recalled': 'rejected'}.get(ending.status,
                                                                                          ending.status)
    found = getattr(ending.result, 'junction_odometry', None)
    return ex.Report(status, ending.message, odometry_mm, ex.found_at(start_odometry_mm, found),
                     bool(getattr(ending.result, 'junction_missing', False)))


class MissionExecutiveNode(object):
    """The mission action server, the command service and the pose on the map."""

    def __init__(self):
        self.settings, self.max_drive_mm = load_settings()
        self.robot = ActionRobot(float(rospy.get_param('~goal_timeout', 600.0)))
        self._lock = threading.Lock()
        self._running = None            # (goal handle, executive, map)
        self._next_level = ex.FULL      # for a goal that names no level; the panel sets it between missions
        self._pose_pub = rospy.Publisher(names.MISSION_POSE_TOPIC, PoseStamped, queue_size=1)
        self._along_pub = rospy.Publisher(names.MISSION_ALONG_TOPIC, Float64, queue_size=1)
        self._uncertainty_pub = rospy.Publisher(names.MISSION_UNCERTAINTY_TOPIC, Float64, queue_size=1)
        self._markers_pub = rospy.Publisher(names.MISSION_MARKERS_TOPIC, MarkerArray, queue_size=2, latch=True)
        self._current_pub = rospy.Publisher(names.MISSION_CURRENT_TOPIC, MissionActionGoal, queue_size=2, latch=True)
        self._log_path = rospy.get_param('~log', os.path.join(rospkg.get_ros_home(), 'pirate', 'mission_log.jsonl'))
        rospy.loginfo('mission_executive: %s (log %s)', self._last_mission(), self._log_path)
        self._log = mission_log.MissionLog(self._log_path)
        self._log_failed = False
        self._cancelled_at = rospy.Time()   # a cancel with no mission running: one sent before is cancelled
        self._server = actionlib.ActionServer(names.MISSION_ACTION, MissionAction, self._on_goal,
                                              self._on_cancel, auto_start=False)
        rospy.Service(names.MISSION_COMMAND_SERVICE, MissionCommand, self._on_command)
        rospy.Timer(rospy.Duration(POSE_PERIOD_S), self._publish_pose)
        self._server.start()
        self._own = actionlib.ActionClient(names.MISSION_ACTION, MissionAction)   # sends the resume goal
        self._resume_goal = None        # its client handle, kept while it runs
        rospy.loginfo('mission_executive ready on %s', names.MISSION_ACTION)

    # --- goals --------------------------------------------------------------
    def _on_goal(self, handle):
        goal, sent = handle.get_goal(), handle.get_goal_id().stamp
        if not sent.is_zero() and sent <= self._cancelled_at:       # the operator's Stop overtook it
            reason = 'cancelled by the operator before it started'
            rospy.loginfo('mission_executive: %s', reason)
            handle.set_canceled(MissionResult(status='cancelled', message=reason), reason)
            return
        try:
            run, pipe_map, accepted = (self._resumed if goal.resume else self._planned)(handle, goal)
        except (network.WorldError, planner.PlanError, ValueError, yaml.YAMLError) as refused:
            self._refuse(handle, str(refused))
            return
        with self._lock:
            if self._running is not None:
                self._refuse(handle, 'a mission is running; cancel it first')
                return
            self._running = (handle, run, pipe_map)
        handle.set_accepted(accepted)
        rospy.loginfo('mission_executive: %s', accepted)
        self._markers_pub.publish(route_markers(pipe_map, run.goal['points']))
        self._current_pub.publish(current_mission(handle.get_goal_id(), run.goal))
        threading.Thread(target=self._run, args=(handle, run), name='mission', daemon=True).start()

    def _planned(self, handle, goal):
        """(executive, map, what acceptance says) of a goal naming its route."""
        level = goal.level or self._next_level
        pipe_map, route_plan, policy = self._prepare(goal, level)
        run = self._executive(handle, route_plan, Localiser(pipe_map.points[goal.points[0]], self.settings),
                              policy, dict(goal_record(goal), level=level), None)
        return run, pipe_map, 'planned: %d PABs' % len(route_plan.steps)

    def _resumed(self, handle, goal):
        """(executive, map, what acceptance says) of a ``resume`` goal: the
        log's interrupted mission; CannotResume (a ValueError) says why not."""
        if goal.map or goal.points:
            raise ValueError('a resume goal takes the map and points of the log; it names none')
        resume, pipe_map, policy = self._take_up()
        run = self._executive(handle, resume.plan, resume.localiser, policy, resume.goal, resume.entry)
        return run, pipe_map, resume.message

    def _take_up(self):
        """(Resume, map, policy) of the log's interrupted mission, from the robot's odometry now."""
        prepared = {}

        def plan_of(goal):
            prepared['map'], route_plan, prepared['policy'] = self._prepare(MissionGoal(**goal), goal['level'])
            return route_plan
        resume = take_up(mission_log.read(self._log_path), plan_of, self.settings, self.robot.odometry_mm)
        return resume, prepared['map'], prepared['policy']

    def _executive(self, handle, route_plan, localiser, policy, goal, entry):
        return ex.Executive(route_plan, self.robot, localiser, self.settings, policy=policy, level=goal['level'],
                            progress=lambda p: self._feedback(handle, p), out=rospy.loginfo, journal=self._journal,
                            name='%s: %s' % (goal['map'], ' -> '.join(goal['points'])), goal=goal, entry=entry)

    def _prepare(self, goal, level):
        """Map, plan and policy of a goal; raises with the reason it cannot run."""
        pipe_map = network.load(network.world_path(goal.map))
        route_plan = planner.plan(pipe_map, list(goal.points), self.settings, self.max_drive_mm,
                                  goal.speed or None, not goal.no_home)
        if level != ex.MANUAL:                      # manual only shows the plan
            planner.check_runnable(route_plan)      # refused now, not stopped at that junction
        policy = yaml.safe_load(goal.policy) if goal.policy else None
        if policy is not None and not isinstance(policy, dict):
            raise ValueError('policy: a mapping {PAB name or default: {retries: N}} is needed, got %r' % policy)
        return pipe_map, route_plan, policy

    def _journal(self, record):
        """One event into the log on disk; a log that cannot be written costs
        the copy on disk (said once), never the mission."""
        try:
            self._log.write(record)
        except (OSError, ValueError) as failed:
            if not self._log_failed:
                self._log_failed = True
                rospy.logwarn('mission_executive: cannot write the log %s: %s', self._log_path, failed)

    def _last_mission(self):
        ending = mission_log.last_ending(mission_log.read(self._log_path))
        hint = '; the command resume takes it up' if ending is not None and ending.status == 'interrupted' else ''
        return mission_log.describe(ending) + hint

    @staticmethod
    def _refuse(handle, reason):
        rospy.logwarn('mission refused: %s', reason)
        handle.set_rejected(MissionResult(status='refused', message=reason), reason)

    def _run(self, handle, run):
        outcome = run.run()
        result = MissionResult(status=outcome.status, message=outcome.message,
                               plan=planner.format_plan(run.plan), log=outcome.log)
        with self._lock:
            self._running = None
        if outcome.status in ('succeeded', 'manual'):
            handle.set_succeeded(result, outcome.message)
        elif outcome.status == 'cancelled' and handle.get_goal_status().status == GoalStatus.PREEMPTING:
            handle.set_canceled(result, outcome.message)
        else:
            handle.set_aborted(result, outcome.message)

    def _on_cancel(self, handle):
        with self._lock:
            running = self._running
        if running is not None and running[0].get_goal_id().id == handle.get_goal_id().id:
            running[1].cancel()

    def _feedback(self, handle, progress):
        if handle is not None and not rospy.is_shutdown():
            handle.publish_feedback(MissionFeedback(
                step=progress.step, steps=progress.steps, pab=progress.pab, option=progress.option,
                distance_mm=progress.distance_mm, along_mm=progress.along_m * 1000,
                time_left_s=progress.time_left_s, level=progress.level, state=progress.state,
                waiting_for=progress.waiting_for))

    # --- the operator -------------------------------------------------------
    def _on_command(self, req):
        with self._lock:
            running = self._running
        word = req.command.strip().lower()
        if running is None and word == 'last':
            ok, message = True, self._last_mission()
        elif running is None and word == 'resume':
            ok, message = self._send_resume()
        elif running is None and word == 'cancel':
            self._cancelled_at = rospy.Time.now()
            ok, message = True, 'no mission is running; one sent before now is cancelled when it comes'
        elif running is None:
            ok, message, self._next_level = ex.between_missions(req.command, self._next_level)
        else:
            ok, message = running[1].command(req.command)
        return MissionCommandResponse(ok=ok, message=message)

    def _send_resume(self):
        """The command ``resume`` between missions: (ok, message). The log's
        mission is checked now, for the operator's answer, then sent to this
        node's action server as a ``resume`` goal, so it runs as any mission."""
        try:
            resume = self._take_up()[0]
        except (CannotResume, network.WorldError, planner.PlanError, ValueError, yaml.YAMLError) as refused:
            return False, 'cannot resume: %s' % refused
        if not wait_for_server(self._own, SERVER_WAIT_S):
            return False, 'cannot resume: the mission action server did not answer'
        self._resume_goal = self._own.send_goal(MissionGoal(resume=True))
        return True, resume.message

    # --- where the robot is -------------------------------------------------
    def _publish_pose(self, _event):
        with self._lock:
            running = self._running
        if running is None or self.robot.odometry_mm is None:
            return
        odometry_mm = self.robot.odometry_mm
        along_m = running[1].localiser.estimate(odometry_mm)
        position, quaternion = pose_along(running[2], along_m)
        pose = PoseStamped()
        pose.header.stamp, pose.header.frame_id = rospy.Time.now(), names.MAP_FRAME
        (pose.pose.position.x, pose.pose.position.y, pose.pose.position.z) = position
        (pose.pose.orientation.x, pose.pose.orientation.y, pose.pose.orientation.z,
         pose.pose.orientation.w) = quaternion
        self._pose_pub.publish(pose)
        self._uncertainty_pub.publish(Float64(data=running[1].localiser.uncertainty_m(odometry_mm) * 1000.0))
        self._along_pub.publish(Float64(data=along_m * 1000.0))


def current_mission(goal_id, goal):
    """The MissionActionGoal of :data:`names.MISSION_CURRENT_TOPIC`: the
    accepted goal's id and its record (a resumed mission's map and points)."""
    msg = MissionActionGoal(goal_id=goal_id, goal=MissionGoal(**goal))
    msg.header.stamp = rospy.Time.now()
    return msg


def goal_record(goal):
    """What the log keeps of a MissionGoal, to take its mission up again."""
    return {'map': goal.map, 'points': list(goal.points), 'speed': goal.speed, 'no_home': goal.no_home,
            'level': goal.level, 'policy': goal.policy}


def _marker(kind, ns, index, rgba, scale, position=(0.0, 0.0, 0.0)):
    marker = Marker(type=kind, action=Marker.ADD, ns=ns, id=index)
    marker.header.frame_id = names.MAP_FRAME
    marker.pose.position.x, marker.pose.position.y, marker.pose.position.z = position
    marker.pose.orientation.w = 1.0
    marker.scale.x, marker.scale.y, marker.scale.z = scale
    marker.color.r, marker.color.g, marker.color.b, marker.color.a = rgba
    return marker


def route_markers(pipe_map, points):
    """The planned route as one line per leg along the pipe's axis, and the
    map's points with their names (RViz, frame ``world``)."""
    out = MarkerArray()
    for index, (a, b) in enumerate(zip(points, points[1:])):
        line = _marker(Marker.LINE_STRIP, 'route', index, ROUTE_RGBA, (LINE_WIDTH_M, 0.0, 0.0))
        line.points = [Point(*xyz) for xyz in path_points(pipe_map, pipe_map.points[a], pipe_map.points[b])]
        out.markers.append(line)
    for index, (name, along_m) in enumerate(sorted(pipe_map.points.items())):
        position = pose_along(pipe_map, along_m)[0]
        label = _marker(Marker.TEXT_VIEW_FACING, 'points', index, (1.0, 1.0, 1.0, 1.0), (0.0, 0.0, 0.04),
                        (position[0], position[1], position[2] + 0.08))
        label.text = name
        out.markers.append(label)
    return out


def main():
    rospy.init_node('mission_executive')
    MissionExecutiveNode()
    rospy.spin()
