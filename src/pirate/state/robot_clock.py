"""The clock an in-process simulated robot's silence is measured on.

:class:`pirate.testing.harness.SimHarness` steps the twin in a thread of
the test's own process. On a loaded machine that thread runs late, and
while it is descheduled the robot's time stands still too: that robot is
late, not silent. (Over ROS the simulated robot runs in lockstep with the
stack on simulated time instead, doc/clock.md; a real robot's silence is
wall time.)

:class:`RobotClock` is the wall clock held back while simulated time stands
still: whoever sees simulated time advance calls :meth:`RobotClock.tick`
(the harness's step loop); more than ``slack_s`` of wall time without a
tick, and the clock stops until the next tick, then goes on from where it
stood. It never jumps: a stall is never counted afterwards as silence. A
simulation running on time ticks far more often than ``slack_s``, so the
clock is the wall clock; a robot that keeps its time running but stops
reporting is noticed after the same wall time as a real one.

Pure Python, no ROS.
"""
import threading
import time

#: s of wall time the clock runs on past the last tick: above the 0.1 s
#: between ticks in the harness (one Mega cycle), below the 0.25-0.3 s the
#: watchdogs wait.
SLACK_S = 0.15


class RobotClock(object):
    """Monotonic seconds that stand still while simulated time does."""

    def __init__(self, wall=time.monotonic, slack_s=SLACK_S):
        self._wall = wall
        self._slack_s = slack_s
        self._lock = threading.Lock()
        self._ticked_at = wall()
        self._held_s = 0.0          # wall s the clock stood still, in total

    def tick(self):
        """Simulated time advanced (now)."""
        with self._lock:
            now = self._wall()
            self._held_s += max(0.0, now - self._ticked_at - self._slack_s)
            self._ticked_at = now

    def __call__(self):
        with self._lock:
            return min(self._wall(), self._ticked_at + self._slack_s) - self._held_s
