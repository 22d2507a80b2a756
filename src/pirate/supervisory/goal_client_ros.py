"""Send one Pirate Server goal and wait for its end: the one helper of the
mission runner (pirate.supervisory.mission_node) and the mission
executive (pirate.supervisory.executive_node).

Why ``actionlib.ActionClient`` and not SimpleActionClient: the simple
client ignores (and logs as an error, "Got a transition callback on a goal
handle that we're not tracking") a status that reaches it before its
``send_goal`` has returned the new handle - which a fast server causes.
Here the transition callback only wakes the waiter, which reads its own
handle, so nothing arrives untracked. :class:`SimpleGoalClient` offers the
simple client's interface that way (the route client, the rostests), and
:class:`GoalClient` waits on it in robot time (the mission runner, the
executive). Neither cancels a goal that has ended: actionlib's
``cancel()`` would leave it waiting for a cancel ack that never comes.

The time limit is robot time (``now``: rospy.get_time, the simulated clock
under /use_sim_time), as the callers' ``~goal_timeout`` / ``--timeout``
say; the wait itself wakes on every transition and at least every 0.1 s
of wall time, so a stopped clock or a shutdown is seen. A goal that ran
out of time, or whose client is shutting down, is cancelled before the
call returns. The client, the clock and the shutdown test are passed in,
so the timeout path is unit-tested without a master.
"""
import collections
import threading
import time

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus

#: Terminal goal states in words.
STATUS = {GoalStatus.SUCCEEDED: 'succeeded', GoalStatus.ABORTED: 'aborted', GoalStatus.PREEMPTED: 'preempted',
          GoalStatus.REJECTED: 'rejected', GoalStatus.RECALLED: 'recalled'}
#: How a goal ended: ``status`` a word of :data:`STATUS`, or ``timeout`` /
#: ``interrupted`` (both cancelled here); ``result`` the Pirate result or None.
Ending = collections.namedtuple('Ending', 'status message result')
WAKE_S = 0.1
#: Where a goal ends only after the server accepted it (active_cb was due).
ACCEPTED_ENDINGS = (GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.PREEMPTED)
#: Client states of a goal the server has not accepted yet.
NOT_YET_ACTIVE = (actionlib.CommState.WAITING_FOR_GOAL_ACK, actionlib.CommState.PENDING,
                  actionlib.CommState.RECALLING)


class GoalClient(object):
    """One Pirate goal at a time, waited for in robot time; :meth:`cancel`
    from any thread. Built on :class:`SimpleGoalClient`, so a cancel that
    meets a goal just ending is not sent (actionlib would then wait for a
    cancel ack that never comes, and :meth:`run` until its time limit)."""

    def __init__(self, client, timeout_s, now, is_shutdown):
        self._goal = SimpleGoalClient(client=client)
        self.timeout_s, self._now, self._is_shutdown = timeout_s, now, is_shutdown

    def run(self, goal):
        """Send ``goal`` and wait for its end: an :data:`Ending`."""
        deadline = self._now() + self.timeout_s
        self._goal.send_goal(goal)
        while not self._goal.wait_ended(WAKE_S):
            if self._is_shutdown() or self._now() >= deadline:
                self._goal.cancel_goal()
                if self._is_shutdown():
                    return Ending('interrupted', 'stopped while the goal ran; goal cancelled', None)
                return Ending('timeout', 'no result within %.0f s; goal cancelled' % self.timeout_s, None)
        result = self._goal.get_result()
        status = STATUS.get(self._goal.get_state(), 'aborted')
        return Ending(status, result.message if result is not None else 'no result', result)

    def cancel(self):
        """Cancel the goal running now, if any (not one that has ended)."""
        self._goal.cancel_goal()


class SimpleGoalClient(object):
    """actionlib.SimpleActionClient's interface on actionlib.ActionClient,
    without its race (module docstring): every state is read from the goal's
    own handle, so a goal that a fast server ended before :meth:`send_goal`
    returned is seen ended. With the simple client such a goal's result was
    dropped and ``wait_for_result`` never returned (CI: a Clamp Straight sent
    to a robot already clamped there succeeds with 0 primitives at once).

    ``client``: an ActionClient (made from ``ns`` and ``spec`` when None),
    kept as ``action_client`` as the simple client keeps its own.
    Callbacks as the simple client's: ``done_cb(state, result)`` once,
    ``active_cb()`` once, ``feedback_cb(feedback)``.
    """

    def __init__(self, ns=None, spec=None, client=None):
        self.action_client = client if client is not None else actionlib.ActionClient(ns, spec)
        self._cond = threading.Condition()
        self._handle = None
        self._callbacks = {}
        self._called = set()          # callbacks called for this goal, and 'ended' once it ended
        self._cancel_due = False      # a cancel asked before the server acknowledged the goal

    def wait_for_server(self, timeout=rospy.Duration()):
        return self.action_client.wait_for_server(timeout)

    def send_goal(self, goal, done_cb=None, active_cb=None, feedback_cb=None):
        """Send ``goal``; from now on this client follows it (no cancel of the last)."""
        with self._cond:
            self._callbacks = {'done': done_cb, 'active': active_cb, 'feedback': feedback_cb}
            self._called = set()
            self._handle, self._cancel_due = None, False
            handle = self.action_client.send_goal(goal, transition_cb=self._on_transition, feedback_cb=self._on_feedback)
            self._handle = handle
            self._catch_up()

    def wait_for_result(self, timeout=rospy.Duration()):
        """True once the goal ended, within ``timeout`` (ROS time, 0: no limit)."""
        if self._handle is None:
            return False
        deadline = rospy.get_rostime() + timeout
        while not self.wait_ended(WAKE_S):
            if (not timeout.is_zero() and rospy.get_rostime() >= deadline) or rospy.is_shutdown():
                return False
        return True

    def wait_ended(self, wall_s):
        """True once the goal ended; False if it has not within ``wall_s``
        wall seconds (woken early by each of its transitions), or no goal was sent."""
        with self._cond:
            if self._handle is not None and not self._ended():
                self._cond.wait(wall_s)
            return self._handle is not None and self._ended()

    def get_state(self):
        """The goal's GoalStatus (LOST before any goal), as the simple client says it."""
        if self._handle is None:
            return GoalStatus.LOST
        status = self._handle.get_goal_status()
        return {GoalStatus.RECALLING: GoalStatus.PENDING, GoalStatus.PREEMPTING: GoalStatus.ACTIVE}.get(status, status)

    def get_result(self):
        return self._handle.get_result() if self._handle is not None else None

    def get_goal_status_text(self):
        return self._handle.get_goal_status_text() if self._handle is not None else ''

    def cancel_goal(self):
        """Cancel the goal unless it ended: actionlib's handle.cancel() on an
        ended goal sets it waiting for a cancel ack that never comes.

        A goal the server has not acknowledged yet is cancelled once it has
        (:meth:`_catch_up`): cancelled at once, actionlib's client waits for
        the cancel's ack and takes the next status array of the server that
        does not list the goal yet (one sent for another goal, or before
        this one arrived) for a goal the server lost: it ends LOST, without
        the result the server then publishes. And the cancel, on its own
        topic, could reach the server before the goal it cancels.
        """
        with self._cond:
            handle = self._handle if self._handle is not None and not self._ended() else None
            if handle is not None and handle.get_comm_state() == actionlib.CommState.WAITING_FOR_GOAL_ACK:
                self._cancel_due, handle = True, None
        if handle is not None:
            handle.cancel()     # outside our lock: actionlib calls our callbacks holding its own

    def _ended(self):
        return 'ended' in self._called or self._handle.get_comm_state() == actionlib.CommState.DONE

    def _on_transition(self, handle):
        with self._cond:
            if self._handle is not None and handle == self._handle:
                self._catch_up()
                if self._cancel_due and handle.get_comm_state() != actionlib.CommState.WAITING_FOR_GOAL_ACK:
                    self._cancel_due = False
                    if not self._ended():
                        handle.cancel()     # actionlib holds the goal's lock here, in this thread

    def _on_feedback(self, handle, feedback):
        with self._cond:
            callback = self._callbacks.get('feedback') if self._handle is not None and handle == self._handle else None
        if callback:
            callback(feedback)

    def _catch_up(self):
        """Call active_cb / done_cb once each for what the handle has reached;
        wake the waiters. Called with the lock held."""
        comm, status = self._handle.get_comm_state(), self._handle.get_goal_status()
        if comm == actionlib.CommState.DONE:
            if status in ACCEPTED_ENDINGS:
                self._call_once('active')
            self._called.add('ended')
            self._call_once('done', self.get_state(), self._handle.get_result())
        elif comm not in NOT_YET_ACTIVE:
            self._call_once('active')
        self._cond.notify_all()

    def _call_once(self, name, *args):
        if name not in self._called and self._callbacks.get(name):
            self._called.add(name)
            self._callbacks[name](*args)


def wait_for_server(client, wall_s):
    """True once ``client``'s action server answers, within ``wall_s`` wall seconds.

    Not actionlib's own timeout: under /use_sim_time a node's clock reads 0
    until its first /clock message, and the first message then jumps past
    any robot-time deadline set before it, so a server that is there was
    reported absent (seen with run_mission started after the twin had run
    for a while). Short waits in a wall-time loop instead.
    """
    deadline = time.monotonic() + wall_s
    while not rospy.is_shutdown():
        if client.wait_for_server(rospy.Duration(WAKE_S)):
            return True
        if time.monotonic() > deadline:
            return False
        time.sleep(WAKE_S)     # pace the polls (actionlib's wait may return at once)
    return False
