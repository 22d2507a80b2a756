"""The clock a robot's silence is measured on.

A real robot's Mega reports on the wall clock whatever the laptop does, so
its silence is wall time (``time.monotonic``). A simulated robot is a
process on the same laptop: on a loaded machine it runs late, and while it
is descheduled its simulated time stands still too. That robot is late, not
silent; measured on the wall clock alone, every watchdog above it (the state
node's silent boards, the server's feedback timeout, the Mega's own
watchdog) fired on a robot that had only fallen behind (CI, load 7 on two
cores: "no robot state for 0.33 s" mid-turn, "boards 21-26 silent" at
start-up).

:class:`RobotClock` is the wall clock held back while simulated time stands
still: whoever sees simulated time advance calls :meth:`RobotClock.tick`
(the simulator's step loop, or a node's timer on sim time); more than
``slack_s`` of wall time without a tick, and the clock stops until the next
tick, then goes on from where it stood. It never jumps: a stall is never
counted afterwards as silence. A simulation running on time ticks far more
often than ``slack_s``, so the clock is the wall clock; a robot that keeps
its time running but stops reporting is noticed after the same wall time as
a real one.

Pure Python, no ROS (``state/clock_ros.py`` is its ROS edge).
"""
import threading
import time

#: s of wall time the clock runs on past the last tick: above the 0.05 s
#: between ticks at x1 (and 0.1 s, one Mega cycle, in the harness), below the
#: 0.25-0.3 s the watchdogs wait.
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
