"""Send one Pirate Server goal and wait for its end: the one helper of the
mission runner (pirate.supervisory.mission_node) and the mission
executive (pirate.supervisory.executive_node).

Why ``actionlib.ActionClient`` and not SimpleActionClient: the simple
client ignores (and logs as an error, "Got a transition callback on a goal
handle that we're not tracking") a status that reaches it before its
``send_goal`` has returned the new handle - which a fast server causes.
Here the transition callback only wakes the waiter, which reads its own
handle, so nothing arrives untracked.

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


class GoalClient(object):
    """One Pirate goal at a time; :meth:`cancel` from any thread."""

    def __init__(self, client, timeout_s, now, is_shutdown):
        self._client, self.timeout_s = client, timeout_s
        self._now, self._is_shutdown = now, is_shutdown
        self._cond = threading.Condition()
        self._handle = None

    def run(self, goal):
        """Send ``goal`` and wait for its end: an :data:`Ending`."""
        deadline = self._now() + self.timeout_s
        with self._cond:
            self._handle = self._client.send_goal(goal, transition_cb=self._wake)
            while not self._done() and not self._is_shutdown() and self._now() < deadline:
                self._cond.wait(WAKE_S)
            handle, self._handle = self._handle, None
        if handle.get_comm_state() != actionlib.CommState.DONE:
            handle.cancel()
            if self._is_shutdown():
                return Ending('interrupted', 'stopped while the goal ran; goal cancelled', None)
            return Ending('timeout', 'no result within %.0f s; goal cancelled' % self.timeout_s, None)
        result = handle.get_result()
        status = STATUS.get(handle.get_goal_status(), 'aborted')
        return Ending(status, result.message if result is not None else 'no result', result)

    def cancel(self):
        """Cancel the goal running now, if any."""
        with self._cond:
            handle = self._handle
        if handle is not None:
            handle.cancel()

    def _done(self):
        return self._handle.get_comm_state() == actionlib.CommState.DONE

    def _wake(self, _handle):
        with self._cond:
            self._cond.notify_all()


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
