"""pirate_manager: one process owning the command arrays (report 4.5, 5.6).

Builds the one Setpoint / Control / Limit, the robot feed, the motion
primitives, the Pirate Server behind an actionlib ActionServer, and the
Mapper (operator panel), so every writer shares the same message state and a
mode switch never resets a setpoint.

Why ``actionlib.ActionServer`` and not SimpleActionServer: a
SimpleActionServer accepts a new goal by preempting the running one; the
report (4.6) wants a goal sent while one runs refused, not queued nor
preempting. The server is created with ``auto_start=False`` and started
when everything is wired. The node that sent the running goal is pinged
while it runs; a goal whose owner is gone is cancelled into the safe hold
(:mod:`pirate.manager.goal_owner`).

Params (private): ``~guards`` ({mm: table}, config/guards_*.yaml),
``~sequencer`` (config/sequencer.yaml), ``~panel`` (bool, compose the
Mapper; its channel map is the rest of the private namespace).
"""
import signal
import sys
import threading
import time

import actionlib
import diagnostic_updater
import dynamic_reconfigure.server
import rospy
from actionlib_msgs.msg import GoalStatus
from std_msgs.msg import Empty, Time

from pirate import health, names
from pirate.robot import commands
from pirate.robot.writers import OneWriter
from pirate.state.assembler import pab_blocker
from pirate.state.feed import RobotFeed, RobotView
from pirate.state.clock_ros import silence_clock
from pirate.panel import manual_guard
from pirate.panel.mapper_ros import MapperRos
from pirate.sequencer.guards import BadConfig, GuardBook
from pirate.msg import (ControlArray, LimitArray, PirateAction, PirateFeedback, PirateGoal,
                        PirateResult, PrimitiveStep, RobotState, SetpointArray, SmallState)
from pirate.cfg import SequencerConfig
from pirate.sequencer import tuning
from pirate.manager.action_server_ros import QuietActionServer
from pirate.manager.goal_owner_ros import OwnerMonitor
from pirate.manager.robot_link import RobotLink
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import ABORTED, PREEMPTED, SUCCEEDED, Feedback, PirateServer
from pirate.srv import CameraPoint, CameraPointResponse, ServerStatus, ServerStatusResponse

SHUTDOWN_FLUSH_S = 0.3
#: Where the manager keeps what the last goal left unfinished (PirateServer.unfinished_data).
UNFINISHED_PARAM = '~unfinished'
#: Where it keeps how the last goal that ran ended (PirateServer.ended_data).
ENDED_PARAM = '~last_goal_ended'
TERMINAL = (GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.PREEMPTED, GoalStatus.RECALLED,
            GoalStatus.REJECTED)


class PabClient(object):
    """The Mapper's handle on the Pirate Server (report 4.6: it is the client).

    Every goal gets the launch's pipe diameter. An ``actionlib.ActionClient``
    whose callback holds its own goal handle: a SimpleActionClient logs a
    spurious error when the fast server's status beats ``send_goal``.
    ``on_result(success, message, refused)`` hears how each goal ended.

    A goal published before the client's action topics reach the server is
    dropped by actionlib without a word (CI: a panel press 30 ms after the
    manager started was "sent" and never ran), so :meth:`connect` waits for
    them once, off the press path, and until then a press is refused at once
    with the reason. Waiting in the press (2 s of ROS time) is only half a
    wall second at sim rate x2 on a busy machine: the press was refused and
    its goal never came.
    """

    def __init__(self, server, pipe_diameter):
        self._server = server
        self._pipe_diameter = pipe_diameter
        self._client = actionlib.ActionClient(names.PIRATE_ACTION, PirateAction)
        self._handle = None     # keeps the goal's handle alive (actionlib tracks it weakly)
        self.connected = threading.Event()
        self.on_result = lambda success, message, refused: None

    def connect(self):
        """Block until the action topics reach the Pirate Server (or shutdown); then goals are sent."""
        if self._client.wait_for_server():
            self.connected.set()
            rospy.loginfo('panel: connected to the Pirate Server: PAB goals from the panel are sent')

    def send_goal(self, goal):
        """Send a :data:`pirate.panel.config.Goal`; (False, reason) when the server would refuse it."""
        if self._server.active:
            return False, 'a PAB is running (%s)' % self._server.active
        if not self.connected.is_set():
            return False, ('the panel is not connected to the Pirate Server yet (its action topics are still '
                           'connecting): nothing was sent; press again')
        self._handle = self._client.send_goal(
            PirateGoal(name=goal.name, pipe_diameter=self._pipe_diameter, distance=goal.distance,
                       speed=goal.speed, option=goal.option), transition_cb=self._transition)
        return True, ''

    def _transition(self, handle):
        if handle.get_comm_state() != actionlib.CommState.DONE:
            return
        result = handle.get_result()
        status = handle.get_goal_status()
        self.on_result(status == GoalStatus.SUCCEEDED, result.message if result else 'no result',
                       status == GoalStatus.REJECTED)

    def cancel(self):
        """Cancel the running goal, whoever sent it (the server's cancel; no
        actionlib cancel-all, which would log errors for goal-less records)."""
        self._server.cancel()

    def is_active(self):
        """True while a PAB runs."""
        return bool(self._server.active)


class PirateManager(object):
    """Everything the pirate_manager process owns."""

    def __init__(self):
        log = rospy.logwarn
        self.control = commands.Control(
            rospy.Publisher(names.CONTROL_TOPIC, ControlArray, queue_size=10, latch=True),
            lambda data: ControlArray(data=data), log=log)
        self.setpoint = commands.Setpoint(
            rospy.Publisher(names.SETPOINT_TOPIC, SetpointArray, queue_size=1),
            lambda data: SetpointArray(data=data), self.control, log=log)
        self.limit = commands.Limit(
            rospy.Publisher(names.LIMITS_TOPIC, LimitArray, queue_size=1),
            lambda data: LimitArray(data=data), log=log)
        book = GuardBook(rospy.get_param('~guards'), rospy.get_param('~sequencer'))
        try:    # the LEDs' duty while goals run; 0: left to the panel's knobs
            self._lights = commands.lights_duty(rospy.get_param('~lights', 0))
        except ValueError as bad:
            raise BadConfig('~lights: %s' % bad)
        self.feed = RobotFeed(book.common['feedback_timeout'], wall_factor=book.common['wall_timeout_factor'],
                              robot_clock=silence_clock())
        self.setpoint.measured = self._measured_angles   # Play holds position joints where they are
        self.prims = MotionPrimitives(self.setpoint, self.control, self.limit, self.feed)
        self.server = PirateServer(self.prims, self.feed, book, self._start_robot,
                                   feedback=self._publish_feedback, log=rospy.loginfo,
                                   pipe_diameter=int(rospy.get_param('~pipe_diameter', 90)),
                                   authority=self._panel_refusal, keep_unfinished=_keep_unfinished,
                                   keep_ended=_keep_ended)
        _restore_unfinished(self.server)
        _restore_ended(self.server)
        self._progress_at = 0.0
        self._closing = threading.Event()
        self._current = None
        self._pending = threading.Condition()
        self._queue = []
        self._action = QuietActionServer(names.PIRATE_ACTION, PirateAction, self._on_goal,
                                         self._on_cancel, auto_start=False)
        rospy.Service(names.SERVER_STATUS_SERVICE, ServerStatus, self._status)
        rospy.Service(names.CAMERA_POINT_SERVICE, CameraPoint, self._point_camera)
        self._lockstep = (rospy.Publisher(names.LOCKSTEP_TOPIC, Time, queue_size=5)
                          if rospy.get_param('/use_sim_time', False) else None)
        rospy.Subscriber(names.ROBOT_STATE_TOPIC, RobotState, self._on_state, queue_size=5)
        self._link = RobotLink(self.setpoint, self.control, self.limit, self.server, self._measured_angles,
                               self._panel_mapper, lambda text: rospy.logwarn('pirate_manager: %s', text))
        self._link_clock = silence_clock()
        rospy.Subscriber(names.SMALL_STATE_TOPIC, SmallState, self._on_small_state, queue_size=50)
        rospy.Subscriber(names.DEVICE_ANNOUNCED_TOPIC, Empty, lambda _msg: self._link.announced(), queue_size=10)
        self._writers = OneWriter(rospy.get_name())
        self._owners = OwnerMonitor(rospy.get_name(), self._owner_gone)
        self._panel_client = None       # the panel's PabClient, when this manager has a panel
        self._diagnostics = self._diagnose()
        for topic, kind in ((names.SETPOINT_TOPIC, SetpointArray), (names.CONTROL_TOPIC, ControlArray),
                            (names.LIMITS_TOPIC, LimitArray)):
            rospy.Subscriber(topic, kind, self._on_command, topic, queue_size=10)
        self.panel = None
        self._manual_guard = manual_guard.ManualGuard(manual_guard.settings(book.common))
        rospy.Timer(rospy.Duration(0.1), self._tick)
        self.panel = self._compose_panel()
        self._reconfigure = self._tunables()
        threading.Thread(target=self._worker, name='pab_worker', daemon=True).start()
        threading.Thread(target=self._owners.run, args=(rospy.is_shutdown,), name='goal_owner', daemon=True).start()
        self._action.start()
        if self._panel_client is not None:
            threading.Thread(target=self._panel_client.connect, name='panel_connect', daemon=True).start()
        rospy.loginfo('pirate_manager ready: guards for %s mm; nothing moves until Play or a PAB goal',
                      ', '.join(str(d) for d in book.diameters()))

    def _compose_panel(self):
        if not rospy.get_param('~panel', True):
            return None
        client = self._panel_client = PabClient(self.server, self.server.pipe_diameter)
        panel = MapperRos(self.setpoint, self.control, self.limit, client, publish_arrays=False)
        client.on_result = panel.mapper.pab_result
        return panel

    def _panel_refusal(self):
        """The panel's veto on goals (stopped), or None without a panel."""
        panel = getattr(self, 'panel', None)
        return panel.mapper.goal_refusal() if panel is not None else None

    def _point_camera(self, req):
        """/pirate/camera/point: the front camera turned, unless the panel is
        stopped or the robot was not started (nothing moves before Play)."""
        refusal = self._panel_refusal() or (None if commands.playing(self.control) else
                                            'the robot is not playing: nothing moves before Play')
        try:
            if refusal:
                raise ValueError(refusal)
            commands.point_camera(self.control, self.setpoint, req.pan, req.tilt)
        except ValueError as why:
            return CameraPointResponse(False, 'camera not turned: %s' % why)
        return CameraPointResponse(True, 'camera turning to pan %.2f rad, tilt %.2f rad' % (req.pan, req.tilt))

    def _diagnose(self):
        """diagnostic_updater: the Pirate Server and the freshness of the robot state, 1 Hz."""
        updater = diagnostic_updater.Updater()
        updater.setHardwareID('pirate')
        updater.add('Pirate Server', lambda stat: health.fill(stat, health.server(
            self.server.status(), self.server.active, self.server.primitive, self.server.cancelled,
            self.server.pipe_diameter)))
        updater.add('robot state', lambda stat: health.fill(stat, health.robot_state(
            self.feed.since_last_state(), self.feed.feedback_timeout)))
        updater.add('command writers', lambda stat: health.fill(stat, health.command_writers(
            self._writers.rogues(time.monotonic()), self._writers.owner)))
        updater.add('goal owner', lambda stat: health.fill(stat, health.goal_owner(
            self._owners.owner, self._owners.lost)))
        updater.add('panel goals', lambda stat: health.fill(stat, health.panel_goals(
            None if self._panel_client is None else self._panel_client.connected.is_set())))
        rospy.Timer(rospy.Duration(1.0), lambda _event: updater.update())
        return updater

    def _tunables(self):
        """dynamic_reconfigure of cfg/Sequencer.cfg, starting from config/sequencer.yaml's values."""
        for name, value in tuning.current(self.server.book.common, self.feed).items():
            if not rospy.has_param('~' + name):
                rospy.set_param('~' + name, value)
        return dynamic_reconfigure.server.Server(SequencerConfig, self._on_tunables)

    def _on_tunables(self, config, _level):
        values = {name: config[name] for name in tuning.NAMES}
        reason = self.server.tune(values)
        if reason:
            rospy.logwarn('tunables refused: %s', reason)
            config.update(tuning.current(self.server.book.common, self.feed))
        return config

    # --- robot side -------------------------------------------------------
    def _on_state(self, msg):
        self._take_state(msg)
        if self._lockstep is not None:      # taken in: the simulator may step on (doc/clock.md)
            if not self._closing.is_set():  # with the cycle's arrays out: a starved 10 Hz timer trips no watchdog
                self.setpoint.tick()
                self.limit.tick()
            self._lockstep.publish(Time(data=msg.header.stamp))

    def _take_state(self, msg):
        blocker = pab_blocker(msg.stale, tuple(bytearray(msg.silent_boards)), float('inf'))
        if blocker:     # old angles are no feedback: the running primitive ends now
            self.feed.lose(blocker)
            return
        stamp = msg.header.stamp.to_sec()
        self.feed.push(RobotView(dict(zip(msg.name, msg.position)), msg.orientation,
                                 msg.odometry, msg.velocity, stamp,
                                 dict(zip(msg.name, msg.effort)),
                                 {'front': msg.odometry_front, 'rear': msg.odometry_rear},
                                 tuple(bytearray(msg.missed_boards))),
                       stamp if self._lockstep is not None else None)   # stamps on /clock, as the feed's clock

    def _on_small_state(self, _msg):
        now = self._link_clock()
        if now:         # simulated time not started yet: no silence to measure
            self._link.heard(now)

    def _panel_mapper(self):
        panel = getattr(self, 'panel', None)     # None until the panel is composed
        return panel.mapper if panel is not None else None

    def _measured_angles(self):
        """Joint angles (rad) of a fresh robot state, or None."""
        view = self.feed.latest()
        return view.angles if view is not None and self.feed.fresh() else None

    def _on_command(self, msg, topic):
        """Every array on the command topics: anyone but this node is a rogue."""
        sender = msg._connection_header.get('callerid', '?')   # pylint: disable=protected-access
        report = self._writers.heard(topic, sender, time.monotonic())
        if report:
            rospy.logerr('pirate_manager: %s', report)
            self.server.cancel(report)
            self.prims.safe_hold()
            self.control.command('stop')
            self._diagnostics.force_update()     # the ERROR on /diagnostics now, not at the next 1 Hz

    def _tick(self, _event):
        if self._closing.is_set():
            return      # shutting down: the safe hold is the last array sent
        self._guard_manual()
        self.setpoint.tick()
        self.limit.tick()
        self._publish_progress()

    def _guard_manual(self):
        """Stop a motor the panel drives without progress (pirate.panel.manual_guard), on robot time."""
        view = self.feed.latest()
        if self.panel is None or view is None or not self.feed.fresh() or view.part_odometry is None:
            return
        driven = self.panel.mapper.manually_driven()
        for motor, why in self._manual_guard.update(view.stamp, driven, view.angles, view.part_odometry):
            self.panel.mapper.stop_stalled(motor, why)

    def _start_robot(self):
        """A goal is a request to move: PLAY and start the 10 Hz arrays (the LEDs at ``~lights``, if set)."""
        commands.play(self.control, self.setpoint, self.limit)
        if self._lights:
            commands.light(self.control, self.setpoint, self._lights)

    # --- action side ------------------------------------------------------
    def _on_goal(self, handle):
        """Accept at most one goal: ``_current`` is set from acceptance until its
        handle is terminal, so no second goal is active meanwhile
        and every cancel of this one finds it."""
        goal = handle.get_goal()
        with self._pending:
            reason = self._busy() or self._writers.refusal(time.monotonic()) or self.server.reserve(goal)
            if not reason:
                handle.set_accepted('accepted')
                self._current = handle
                self._owners.watch(handle)
                self._queue.append(handle)
                self._pending.notify()
        if reason:
            rospy.logwarn('goal refused: %s', reason)
            handle.set_rejected(PirateResult(success=False, message=reason, junction_odometry=float('nan')), reason)

    def _busy(self):
        """Reason while the current goal's handle is not terminal yet."""
        if self._current is None or self._current.get_goal_status().status in TERMINAL:
            return None
        return 'a PAB is running (goal %s is ending): goals are not queued' % self._current.get_goal_id().id

    def _on_cancel(self, handle):
        if handle.get_goal() is None:   # a cancel of a goal not received yet: actionlib recalls it
            return
        with self._pending:
            if self._current is not None and handle.get_goal_id().id == self._current.get_goal_id().id:
                self.server.cancel()

    def _worker(self):
        while not rospy.is_shutdown():
            with self._pending:
                while not self._queue:
                    self._pending.wait(0.5)
                    if rospy.is_shutdown():
                        return
                handle = self._queue.pop(0)
            outcome = self.server.run(handle.get_goal())
            result = self._result(outcome)
            if outcome.status == SUCCEEDED:
                handle.set_succeeded(result, outcome.message)
            elif outcome.status == PREEMPTED:
                handle.set_canceled(result, outcome.message)
            else:
                assert outcome.status == ABORTED
                handle.set_aborted(result, outcome.message)
            self._owners.release(handle)
            with self._pending:
                if self._current is handle:
                    self._current = None     # only now: the handle is terminal

    def _owner_gone(self, handle, reason):
        """The node that sent the running goal is gone (pirate.manager.goal_owner):
        cancel it into the safe hold and say so now."""
        with self._pending:
            if self._current is not handle:
                return
            self.server.cancel(reason)
        rospy.logerr('pirate_manager: %s', reason)
        self.prims.safe_hold()
        self._diagnostics.force_update()     # the ERROR on /diagnostics now, not at the next 1 Hz

    def _result(self, outcome):
        """The result: success, message, the trace of primitives, the state after,
        where a junction PAB sensed its junction."""
        steps = [PrimitiveStep(name=s.name, guard=s.guard, start=s.start, end=s.end, outcome=s.outcome)
                 for s in self.server.trace.steps]
        return PirateResult(success=outcome.status == SUCCEEDED, message=outcome.message,
                            primitives=steps, server_state=self.server.status(),
                            junction_odometry=outcome.junction_odometry, junction_missing=outcome.junction_missing)

    def _publish_feedback(self, fb, progress=None):
        handle = self._current
        if handle is not None and not rospy.is_shutdown():
            msg = PirateFeedback(server_state=fb.server_state, pab_state=fb.pab_state,
                                 primitive=fb.primitive, guard=fb.guard)
            if progress is not None:
                msg.elapsed, msg.timeout = progress.elapsed, progress.timeout
                msg.guard_joints, msg.guard_values, msg.guard_thresholds = progress.guard
            handle.publish_feedback(msg)

    def _publish_progress(self):
        """Feedback with numbers (time against timeout, guard against threshold), 2 Hz robot time."""
        progress = self.server.progress()
        if progress is None or abs(progress.elapsed - self._progress_at) < 0.5:
            return
        self._progress_at = progress.elapsed
        self._publish_feedback(Feedback(self.server.status(), self.server.pab_state,
                                        progress.primitive, progress.guard_text), progress)

    def _status(self, _req):
        return ServerStatusResponse(active=bool(self.server.active), cancelled=self.server.cancelled,
                                    server_state=self.server.status(), pab_state=self.server.pab_state,
                                    primitive=self.server.primitive, robot_connected=self.feed.fresh())

    # --- shutdown ---------------------------------------------------------
    def shutdown(self, *_signal):
        """SIGINT/SIGTERM: cancel, publish the safe hold, let it reach the wire."""
        self._closing.set()
        self.server.cancel()
        self.prims.safe_hold()
        time.sleep(SHUTDOWN_FLUSH_S)   # give the publisher thread time to send it
        rospy.signal_shutdown('pirate_manager stopped: safe hold sent')


def _keep(param, data):
    """``data`` in the private parameter ``param``, deleted when None: a
    parameter outlives this node, so a manager started again under the same
    master takes it back (a master that does not answer: the server logs it)."""
    if data is not None:
        rospy.set_param(param, data)
    elif rospy.has_param(param):
        rospy.delete_param(param)


def _keep_unfinished(data):
    """What the last goal left unfinished: a manager started again still finishes a turn."""
    _keep(UNFINISHED_PARAM, data)


def _keep_ended(data):
    """How the last goal ended: Home and Drive from a manager started again
    half round a corner are still refused where the turn stopped."""
    _keep(ENDED_PARAM, data)


def _restore(param, restore, said):
    """Take back what the manager before this one kept in ``param`` with
    ``restore`` (a PirateServer method), then log ``said()``: what was taken,
    as the server now holds it; or drop it with why."""
    if not rospy.has_param(param):
        return
    data = rospy.get_param(param)
    reason = restore(data)
    if reason is None:
        rospy.loginfo('kept from the last run of this node: %s', said())
    else:
        rospy.logwarn('dropped %s (%r): %s', param, data, reason)
        rospy.delete_param(param)


def _restore_unfinished(server):
    _restore(UNFINISHED_PARAM, server.restore_unfinished, lambda: '%(goal)s left unfinished %(record)s; re-sent, '
             'it goes on from there' % server.unfinished_data())


def _restore_ended(server):
    _restore(ENDED_PARAM, server.restore_ended, lambda: 'the last goal, %(pab)s, ended %(status)s in %(state)s at '
             'odometry %(odometry_mm).0f mm' % server.ended_data())


def main():
    rospy.init_node('pirate_manager', disable_signals=True)
    asked = []              # a stop asked while starting (the action server is up before the end): kept
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_signal: asked.append(True))
    try:
        manager = PirateManager()
    except BadConfig as bad:        # a bad safety setting: refuse to start, say which
        rospy.logfatal('pirate_manager not started: %s (config/sequencer.yaml, the launch)', bad)
        rospy.signal_shutdown(str(bad))
        sys.exit(2)
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, manager.shutdown)
    if asked:
        manager.shutdown()
    rospy.spin()
