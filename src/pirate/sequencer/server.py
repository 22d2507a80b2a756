"""Pirate Server (report 4.7, 5.8): checks goals, runs PABs, one exit path.

Pure Python; :mod:`pirate.manager.manager_node` wires it to an actionlib
ActionServer. Rules:
- while the operator panel is stopped (``authority``) every goal, from any
  client, is refused with that reason;
- a goal it cannot do is refused at once with the reason (unknown or
  unbuilt PAB, no guards for the diameter, out-of-range drive, robot not
  clamped for Drive, no robot state, another goal running — never queued);
- :meth:`run` has one exit path: whatever ends the PAB (success, cancel,
  timeout, lost feedback, a refused primitive, a bug) it returns exactly one
  outcome, and every outcome but success leaves the robot in the safe hold;
- the server's own state follows Fig 4.2: the running PAB, or, when idle,
  Idle Clamped / Idle Unclamped / Idle Partly Clamped as the robot senses
  it (:mod:`pirate.sequencer.clamp_state`), whatever ended the last goal;
- every primitive a goal runs is kept in :attr:`trace` (robot times and
  outcome) for the result, because feedback may be lost on the way;
- what a goal that did not succeed leaves unfinished (``Pab.unfinished``:
  a turn cancelled once its rear came round, which nothing sensed tells
  from a robot in a straight pipe) is handed to the same goal re-sent
  next, and dropped when any other goal runs; ``keep_unfinished`` is told
  every change (as plain data, :meth:`unfinished_data`) so a restarted
  manager can take it back (:meth:`restore_unfinished`);
- how the last goal that ran ended (``Pab.follows``: its PAB state and the
  odometry then) is told to the next PAB before its check (Home and Drive
  refuse to start in a corner a turn stopped in); ``keep_ended`` is told it as
  plain data (:meth:`ended_data`) so a restarted manager can take it back
  (:meth:`restore_ended`).
"""
import collections
import math
import threading
import traceback

from pirate.state import feed as feeds
from pirate.robot import safety
from pirate.sequencer import clamp_state, goals, tuning
from pirate.sequencer.guards import NoGuards
from pirate.sequencer.pabs import PABS
from pirate.sequencer.pabs.base import Ended, PabFailed
from pirate.sequencer.primitives import Refused
from pirate.sequencer.trace import REACHED, Trace, guard_numbers

IDLE_UNCLAMPED = clamp_state.IDLE_UNCLAMPED
IDLE_CLAMPED = clamp_state.IDLE_CLAMPED
SUCCEEDED, ABORTED, PREEMPTED = 'succeeded', 'aborted', 'preempted'

#: How a goal ended. ``junction_odometry`` (mm of odometry from the goal's
#: start to where a junction PAB sensed its junction, NaN when none) and
#: ``junction_missing`` (it looked the goal's whole distance and found none)
#: go into the action result for the supervisory layer's map check.
Outcome = collections.namedtuple('Outcome', 'status message junction_odometry junction_missing',
                                 defaults=(math.nan, False))
Feedback = collections.namedtuple('Feedback', 'server_state pab_state primitive guard')
#: The numbers of a running primitive: robot time since it started against
#: its timeout (s), and its guard's joints, values and thresholds (rad).
Progress = collections.namedtuple('Progress', 'primitive guard_text elapsed timeout guard')


class PabContext(object):
    """What a running PAB works with."""

    def __init__(self, prims, feed, guards, goal, report):
        self.prims = prims
        self.feed = feed
        self.guards = guards
        self.goal = goal
        self.report = report


def _goal_key(goal):
    """What makes a re-sent goal the same goal."""
    return goal.name, goal.option, goal.pipe_diameter


def robot_clamped(view, guards):
    """True when both parts are fully clamped as the robot senses it (angles and springs)."""
    return clamp_state.sensed(guards, view) == (clamp_state.FULL, clamp_state.FULL)


def _read_back(parse, data, what):
    """(``parse(data)``, None), or (None, why ``data`` is not ``what``): data
    a restarted manager kept, refused whole when it is not what it says."""
    try:
        return parse(data), None
    except KeyError as missing:
        return None, 'not %s: no %s' % (what, missing)
    except (TypeError, ValueError) as bad:
        return None, 'not %s: %s' % (what, bad)


def _unfinished_from(data):
    """(goal key, record) from :meth:`PirateServer.unfinished_data`."""
    name, option, diameter = (int(value) for value in data['goal'])
    if PABS.get(name, (None, None))[1] is None:
        raise ValueError('no PAB with code %d' % name)
    return (name, option, diameter), PABS[name][1].record_from(dict(data['record']))


def _ended_from(data):
    """The :data:`Ended` whose fields ``data`` (a dict) holds; KeyError,
    TypeError or ValueError (naming the field) when it is not one."""
    required = [data[field] for field in Ended._fields[:-1]]
    ended = Ended(*required, junction_missing=data.get('junction_missing', False))
    if not isinstance(ended.pab, str) or not ended.pab:
        raise TypeError('pab %r is not the name of a PAB' % (ended.pab,))
    if not isinstance(ended.state, str):
        raise TypeError('state %r is not a PAB state' % (ended.state,))
    if ended.status not in (SUCCEEDED, ABORTED, PREEMPTED):
        raise ValueError('status %r is none of %s, %s, %s' % (ended.status, SUCCEEDED, ABORTED, PREEMPTED))
    if not isinstance(ended.junction_missing, bool):
        raise TypeError('junction_missing %r is not true or false' % (ended.junction_missing,))
    return ended._replace(odometry_mm=float(ended.odometry_mm))


class PirateServer(object):
    """Goal checking, PAB execution and the server state machine."""

    def __init__(self, prims, feed, book, start_robot, feedback=None, log=None,
                 pipe_diameter=90, authority=None, keep_unfinished=None, keep_ended=None):
        self.prims = prims
        self.feed = feed
        self.book = book
        self._start_robot = start_robot
        self._feedback = feedback or (lambda fb: None)
        self._log = log or (lambda text: None)
        self._lock = threading.Lock()
        self._authority = authority or (lambda: None)   # the panel: a reason no goal may move
        self.pipe_diameter = pipe_diameter  # mm, of the last goal: the idle state's guards
        self.state = None           # the running PAB; None when idle (see :meth:`status`)
        self.active = None          # name of the running PAB
        self.pab_state = ''
        self.primitive = ''
        self.trace = Trace()
        self._guards = None
        self._tuning = None         # tunables waiting for the running goal to end
        self._unfinished = None     # (goal key, record) of the last goal, ended without success
        self._ended = None          # Ended: how the last goal that ran ended, for the next PAB
        self._keep_unfinished = keep_unfinished or (lambda data: None)
        self._keep_ended = keep_ended or (lambda data: None)
        prims.notify = self._on_primitive

    # --- accepting --------------------------------------------------------
    def reserve(self, goal):
        """Check ``goal`` and, if it can run, mark it running. Return a reason or None."""
        with self._lock:
            reason = self._authority() or self._check(goal)
            if reason is None:
                self.active = PABS[goal.name][0]
                self.feed.clear_cancel()
            return reason

    def _check(self, goal):
        if self.active:
            return 'a PAB is running (%s): cancel it first; goals are not queued' % self.active
        if goal.name not in PABS:
            return 'unknown PAB code %r (known: %s)' % (goal.name, ', '.join(
                '%d %s' % (code, row[0]) for code, row in sorted(PABS.items())))
        name, pab_class = PABS[goal.name]
        if pab_class is None:
            return 'PAB %s is not implemented yet' % name
        refusal = goals.option_refusal(goal.name, goal.option)
        if refusal:
            return refusal
        try:
            guards = self.book.for_diameter(goal.pipe_diameter)
        except NoGuards as missing:
            return '%s: %s' % (name, missing)
        view = self.feed.latest()
        if self.feed.lost_reason:
            return '%s: robot state stale (%s); the robot is not fully known' % (name, self.feed.lost_reason)
        if view is None or not self.feed.fresh():
            return '%s: no robot state (is the robot connected and the state node running?)' % name
        if pab_class.requires_clamped and not robot_clamped(view, guards):
            front, rear = clamp_state.sensed(guards, view)
            # the diameter is named: clamped in 90 mm, a 110 mm goal reads the robot as unclamped
            return ('%s needs the robot clamped (%s); by the %d mm guards it senses the front part %s, the rear %s'
                    % (name, IDLE_CLAMPED, guards.pipe_diameter, front, rear))
        return self._pab_for(goal).check(goal, view, guards)

    def _pab_for(self, goal):
        """The PAB for ``goal``, given what the same goal's last run left unfinished."""
        pab = PABS[goal.name][1].for_goal(goal)
        pab.follows(self._ended)
        key, record = self._unfinished or (None, None)
        if key == _goal_key(goal):
            pab.carry_on(record)
        return pab

    # --- what a goal left unfinished, across a restart -------------------
    def unfinished_data(self):
        """What the last goal left unfinished as plain data (a ROS parameter can
        hold it): {'goal': [name, option, pipe_diameter], 'record': {...}}, or None."""
        if self._unfinished is None:
            return None
        key, record = self._unfinished
        return {'goal': list(key), 'record': dict(record._asdict())}

    def restore_unfinished(self, data):
        """Take back :meth:`unfinished_data` kept by a manager that restarted;
        return why it cannot be taken (and keep nothing), or None. The record
        only applies while the odometry lies in its span (the PAB checks), so
        one the robot has moved away from since does nothing."""
        self._unfinished, reason = _read_back(_unfinished_from, data, 'a record of an unfinished goal')
        return reason

    def _set_unfinished(self, unfinished):
        """Keep ``unfinished``; tell ``keep_unfinished`` when it changed."""
        changed = unfinished != self._unfinished
        self._unfinished = unfinished
        if changed:
            self._hand_over(self._keep_unfinished, self.unfinished_data(), 'what the goal left unfinished')

    # --- how the last goal ended, across a restart -----------------------
    def ended_data(self):
        """How the last goal that ran ended as plain data (the fields of
        :data:`Ended`, a ROS parameter can hold them), or None."""
        return None if self._ended is None else dict(self._ended._asdict())

    def restore_ended(self, data):
        """Take back :meth:`ended_data` kept by a manager that restarted;
        return why it cannot be taken (and keep nothing), or None. Home and
        Drive read it only while the odometry has not moved from where that goal ended,
        so one the robot has driven away from since does nothing."""
        self._ended, reason = _read_back(_ended_from, data, 'a record of how a goal ended')
        return reason

    def _set_ended(self, ended):
        self._ended = ended
        self._hand_over(self._keep_ended, self.ended_data(), 'how the goal ended')

    def _hand_over(self, keep, data, what):
        """Tell ``keep`` of ``data``. Called after the safe hold (keeping may
        wait on the ROS master); one that fails costs the copy kept outside,
        never the goal's one outcome."""
        try:
            keep(data)
        except Exception as lost:  # pylint: disable=broad-except; the one exit path must hold
            self._log('could not keep %s (%s): %s' % (what, data, lost))

    def cancel(self, reason=None):
        """Cancel the running goal; the PAB stops at its next wake-up.
        ``reason``: why, when not the operator (the goal's result says it)."""
        self.feed.cancel(reason)

    @property
    def cancelled(self):
        """True when the running goal has been asked to cancel."""
        return bool(self.active) and self.feed.cancelled

    # --- running ----------------------------------------------------------
    def run(self, goal):
        """Run a reserved goal to its one :data:`Outcome`."""
        guards = self.book.for_diameter(goal.pipe_diameter)
        pab = self._pab_for(goal)
        self.prims.use(guards)
        self.state = pab.name
        self.pipe_diameter, self._guards, self.trace = goal.pipe_diameter, guards, Trace()
        outcome = Outcome(ABORTED, '%s did not start' % pab.name)
        try:
            self._start_robot()
            ctx = PabContext(self.prims, self.feed, guards, goal, self._report)
            outcome = Outcome(SUCCEEDED, '%s: %s' % (pab.name, pab.run(ctx)))
        except feeds.Cancelled:
            why = ': %s' % self.feed.cancel_reason if self.feed.cancel_reason else ''
            outcome = Outcome(PREEMPTED, '%s cancelled during %s%s' % (pab.name, self.pab_state, why))
        except (feeds.TimedOut, feeds.FeedbackLost, PabFailed, Refused, NoGuards, safety.Refused) as failure:
            outcome = Outcome(ABORTED, '%s aborted in %s: %s' % (pab.name, self.pab_state, failure))
        except Exception as bug:  # pylint: disable=broad-except; a bug must still end safe
            outcome = Outcome(ABORTED, '%s aborted by an internal error: %r' % (pab.name, bug))
            self._log(traceback.format_exc())
        finally:
            outcome = outcome._replace(junction_odometry=getattr(pab, 'junction_odometry', math.nan),
                                       junction_missing=getattr(pab, 'junction_missing', False))
            if outcome.status != SUCCEEDED:
                self.prims.safe_hold()
            record = pab.unfinished() if outcome.status != SUCCEEDED else None
            self._set_ended(Ended(pab.name, self.pab_state, self._odometry_now(), outcome.status,
                                  outcome.junction_missing))
            self._set_unfinished((_goal_key(goal), record) if record is not None else None)
            self.trace.end(self._robot_now(), outcome.status)
            self._finish(outcome)
        return outcome

    def tune(self, values):
        """New tunables (dynamic_reconfigure): applied now when idle, else after this goal.

        Returns the reason they were refused, or None.
        """
        with self._lock:
            reason = tuning.problem(values, self.book.common)
            if reason is None:
                self._tuning = dict(values)
                if not self.active:
                    self._apply_tuning()
            return reason

    def _apply_tuning(self):
        if self._tuning is not None:
            tuning.apply(self._tuning, self.book.common, self.feed)
            self._log('tunables applied: %s' % ', '.join('%s %g' % kv for kv in sorted(self._tuning.items())))
            self._tuning = None

    def _finish(self, outcome):
        self._log(outcome.message)
        with self._lock:
            self.active = self.state = None
            self.pab_state = self.primitive = ''
            self._apply_tuning()
        self._feedback(Feedback(self.status(), '', '', ''))

    def status(self):
        """The server state: the running PAB, else the idle state the robot senses."""
        running = self.state
        if running:
            return running
        view = self.feed.latest()
        if view is None:
            return 'Idle (no robot state)'
        try:
            guards = self.book.for_diameter(self.pipe_diameter)
        except NoGuards as missing:
            return 'Idle (%s)' % missing
        return clamp_state.idle_state(clamp_state.sensed(guards, view))

    def progress(self):
        """:data:`Progress` of the running primitive, or None when none runs."""
        step, view, guards = self.trace.running, self.feed.latest(), self._guards
        if step is None or view is None or guards is None or not self.active:
            return None
        return Progress(step.name, step.guard, view.stamp - step.start, guards.primitive_timeout,
                        guard_numbers(step.guard, view.angles))

    def _odometry_now(self):
        view = self.feed.latest()
        return view.odometry if view is not None else math.nan

    def _robot_now(self):
        view = self.feed.latest()
        return view.stamp if view is not None else 0.0

    def _report(self, pab_state, guard=''):
        self.pab_state = pab_state
        self._feedback(Feedback(self.state, pab_state, self.primitive, guard))

    def _on_primitive(self, primitive, guard):
        self.primitive = primitive
        if primitive:
            self.trace.start(primitive, guard, self._robot_now())
        else:
            self.trace.end(self._robot_now(), REACHED)
        self._feedback(Feedback(self.state, self.pab_state, primitive, guard))
