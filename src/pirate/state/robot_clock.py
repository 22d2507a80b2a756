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

:class:`RobotClock` is the wall clock held back to at most ``slack_s`` past
the last instant simulated time was seen to advance. A simulation running on
time ticks far more often than that (``/clock`` every 20 ms of simulated
time), so the clock is the wall clock; a robot that keeps its time running
but stops reporting is noticed after the same wall time as a real one. A
simulation slower than x1 only makes the watchdogs later, never earlier.

Pure Python, no ROS: the nodes pass ``rospy.get_time`` (sim time), the
in-process harness its robot time.
"""
import threading
import time

#: s of wall time the clock runs on past the last advance of simulated time:
#: above the 0.1 s a Mega cycle takes at x1 (the slowest rate in use ticks
#: /clock every 20 ms), below the 0.25-0.3 s the watchdogs wait.
SLACK_S = 0.15


class RobotClock(object):
    """Monotonic seconds that stand still while simulated time does, and go
    on from where they stood when it moves again (a stall is never counted
    afterwards as silence)."""

    def __init__(self, sim_time, wall=time.monotonic, slack_s=SLACK_S):
        self._sim_time = sim_time
        self._wall = wall
        self._slack_s = slack_s
        self._lock = threading.Lock()
        self._last_sim = sim_time()
        self._advanced_at = wall()
        self._held_s = 0.0          # wall s the clock stood still, in total

    def __call__(self):
        with self._lock:
            now = self._wall()
            hold_from = self._advanced_at + self._slack_s
            sim = self._sim_time()
            if sim != self._last_sim:
                # Queries may be sparse: of the wall time since the hold began,
                # the part simulated time covers was running time (at a rate of
                # at least x1), the rest stood still.
                self._held_s += max(0.0, now - hold_from - max(0.0, sim - self._last_sim))
                self._last_sim, self._advanced_at = sim, now
                return now - self._held_s
            return min(now, hold_from) - self._held_s


def silence_clock(use_sim_time, sim_time):
    """The clock for a node's watchdogs: :class:`RobotClock` over ``sim_time``
    when the robot is simulated (``use_sim_time``), else the wall clock."""
    return RobotClock(sim_time) if use_sim_time else time.monotonic
