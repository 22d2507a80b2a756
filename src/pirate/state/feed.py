"""The robot's state as the sequencer sees it, and event-driven waiting on it.

Advanced motion primitives publish, then wait for a guard on the joint
angles (report 4.7.2). :meth:`RobotFeed.wait_until` wakes on every new
state, on cancel, and a few times a second to check two clocks:

- the primitive's timeout runs on *robot* time, the stamps of the states
  themselves, so a simulated robot running faster than real time keeps the
  report's 15 s;
- the feedback watchdog runs on ``robot_clock`` (below): when states stop
  arriving the wait ends with
  :class:`FeedbackLost` within ``feedback_timeout`` plus one poll; a state
  reported stale (a silent board, :meth:`RobotFeed.lose`) ends it at once;
- every wait also has a wall-clock bound (``wall_factor`` x its timeout),
  so no primitive outlives its timeout because robot time stopped or
  crawls.

The watchdog's silence is measured on ``robot_clock`` (default: the wall
clock): for a simulated robot, simulated time, which the simulator advances
in lockstep with the stack (doc/clock.md), so a late stack or simulator is
not taken for a silent robot. ``wait(cond, poll_s)`` is how a wait sleeps
between its checks (default: ``poll_s`` of the wall clock); the in-process
twin (pirate.testing.harness) passes its own, which returns at the robot's
next cycle.

Pure Python: no ROS; the manager pushes states in.
"""
import collections
import math
import threading
import time

#: One state of the robot in SI units. ``angles`` maps joint name -> rad,
#: ``orientation`` is the rear part's roll (rad, Fig 4.7), ``odometry`` mm
#: (NaN when the robot reports none), ``stamp`` robot time in s, ``efforts``
#: joint name -> spring effort in mNm (None when the source has no springs;
#: the clamp state needs them: a clamp means pressing the wall),
#: ``part_odometry`` part name ('front' / 'rear') -> that part's own wheels'
#: odometry in mm (None when the source has none; pirate.state.odometry),
#: ``missed_boards`` the boards whose latest reply is missing (their values held).
RobotView = collections.namedtuple('RobotView',
                                   'angles orientation odometry velocity stamp efforts part_odometry missed_boards',
                                   defaults=(None, None, ()))

POLL_S = 0.02


def _wall_wait(cond, poll_s):
    cond.wait(poll_s)


class Interrupted(Exception):
    """A wait ended without its guard: base of the reasons below."""


class Cancelled(Interrupted):
    """The operator cancelled the running goal."""


class TimedOut(Interrupted):
    """The guard was not reached within the primitive's timeout."""


class FeedbackLost(Interrupted):
    """The robot's state stopped arriving."""


class SensorFrozen(FeedbackLost):
    """A joint's readings stand still while it is driven: its sensor is stuck."""


class RobotFeed(object):
    """Newest :data:`RobotView`, cancel flag, and guard waiting."""

    def __init__(self, feedback_timeout=0.3, clock=time.monotonic, wall_factor=2.0, robot_clock=None, wait=None):
        self.feedback_timeout = feedback_timeout
        self.wall_factor = wall_factor
        self._clock = clock
        self._robot_clock = robot_clock or clock
        self._wait = wait or _wall_wait
        self._cond = threading.Condition()
        self._latest = None
        self._arrival = -math.inf
        self._cancelled = False
        self.cancel_reason = None   # who or what cancelled, when not the operator
        self._lost = None           # why the newest state is unusable, or None
        self._watch = lambda view: None

    def watch(self, check):
        """Every wait calls ``check(view)`` on each state before its guard
        (it raises to end the wait, e.g. :class:`SensorFrozen`)."""
        self._watch = check

    def push(self, view, sent_s=None):
        """A new state from the robot (called by the subscriber); ``sent_s``:
        when it was sent on the robot's clock, if that clock is the one
        silence is judged on (simulated time: a subscriber whose /clock lags
        takes the newer of the two)."""
        with self._cond:
            self._latest = view
            self._arrival = self._robot_clock() if sent_s is None else max(self._robot_clock(), sent_s)
            self._lost = None
            self._cond.notify_all()

    def lose(self, reason):
        """The robot reported its state stale (``reason`` names the silent boards)."""
        with self._cond:
            self._lost = reason
            self._cond.notify_all()

    @property
    def lost_reason(self):
        """Why the state is not usable now (a silent board), or None."""
        with self._cond:
            return self._lost

    def latest(self):
        """The newest state, or None before the first."""
        with self._cond:
            return self._latest

    def fresh(self):
        """True when a state arrived within the feedback timeout."""
        with self._cond:
            return self._lost is None and self._robot_clock() - self._arrival <= self.feedback_timeout

    def since_last_state(self):
        """Seconds of the robot's clock since the newest state (inf before the first)."""
        with self._cond:
            return self._robot_clock() - self._arrival

    def cancel(self, reason=None):
        """Ask the running wait (and every later one) to end at once;
        ``reason``: why, when not the operator (e.g. a rogue writer)."""
        with self._cond:
            self._cancelled = True
            self.cancel_reason = reason or self.cancel_reason
            self._cond.notify_all()

    def clear_cancel(self):
        """Ready for the next goal."""
        with self._cond:
            self._cancelled, self.cancel_reason = False, None

    @property
    def cancelled(self):
        """True once :meth:`cancel` was called for this goal."""
        return self._cancelled

    def check(self):
        """Raise Cancelled or FeedbackLost if either holds now."""
        with self._cond:
            self._check_locked()

    def _check_locked(self):
        if self._cancelled:
            raise Cancelled(self.cancel_reason or 'cancelled by the operator')
        if self._lost is not None:
            raise FeedbackLost('robot state stale: %s' % self._lost)
        silent = self._robot_clock() - self._arrival
        if silent > self.feedback_timeout:
            raise FeedbackLost('no robot state for %.2f s (limit %.2f s)'
                               % (silent, self.feedback_timeout))

    def wait_until(self, guard, timeout, describe='guard'):
        """Block until ``guard(view)`` holds; return that view.

        Raises :class:`Cancelled`, :class:`FeedbackLost`, or :class:`TimedOut`
        after ``timeout`` s of robot time without the guard.
        """
        with self._cond:
            start, wall_end = None, self._clock() + self.wall_factor * timeout
            while True:
                self._check_locked()
                view = self._latest
                if view is not None:
                    self._watch(view)
                    if guard(view):
                        return view
                    start = view.stamp if start is None else start
                    if view.stamp - start > timeout:
                        raise TimedOut('%s not reached within %.1f s' % (describe, timeout))
                if self._clock() > wall_end:
                    raise TimedOut('%s not reached within %.1f s of wall clock (%.0f x its %.1f s)'
                                   % (describe, self.wall_factor * timeout, self.wall_factor, timeout))
                self._wait(self._cond, POLL_S)
