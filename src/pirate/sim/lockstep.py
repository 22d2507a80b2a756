"""Lockstep between a simulated robot and the stack (doc/clock.md).

The simulator owns simulated time (``/clock``). After it publishes a Mega
cycle's Small States it waits until the stack has consumed them - the
manager acknowledges each robot state it takes in - before it steps on.
So simulated time never runs more than one Mega cycle past the newest state
the manager holds, whatever the laptop's load: a descheduled consumer is
late, and its watchdogs, judging silence on simulated time, see no silence.

Which acknowledgement is of the newest cycle: the state node publishes one
state per cycle, made from that cycle's Small States, so once a cycle was
acknowledged the next acknowledgement is of the next cycle, whatever its
stamp (a consumer's clock lags /clock by up to a whole cycle on a busy
machine). Only after the simulator stepped on unacknowledged may a late
acknowledgement of an earlier cycle come, and then the stamp decides.

The wait has a wall-clock bound, so a stack that is frozen (not dead: a dead
consumer drops its connections, and the simulator stops waiting for it at
once) still sees the robot go on and its Mega watchdog trip on simulated
time.

Pure Python, no ROS: the simulator node passes in whether anyone consumes.
"""
import threading
import time

#: Wall s the simulator waits for the stack per Mega cycle before it steps
#: on: far above a cycle's work at a load of 4 processes per core (tens of
#: ms), so only a frozen stack ever reaches it.
WAIT_BOUND_S = 1.0
#: After a cycle the simulator stepped on unacknowledged: how much older
#: than the cycle an acknowledged state's stamp may be and still be of that
#: cycle, simulated s. Just under a Mega cycle (0.1 s): a consumer's clock
#: lags /clock while its clock thread waits for the CPU
#: (measurements.md#lockstep-stamp-lag); an acknowledgement of the cycle
#: before, arriving late, is older still.
STAMP_SLACK_S = 0.09


class Lockstep(object):
    """One Mega cycle at a time: published, then acknowledged (or the bound)."""

    def __init__(self, bound_s=WAIT_BOUND_S, wall=time.monotonic):
        if not bound_s > 0:
            raise ValueError('lockstep bound %r s: must be above 0' % (bound_s,))
        self.bound_s = bound_s
        self.overruns = 0           # cycles the simulator stepped on unacknowledged
        self.heard = False          # a consumer acknowledged a cycle (one is there and subscribed)
        self.lag_s = None           # how far the newest acknowledgement's stamp lay behind its cycle, s
        self.worst_lag_s = 0.0      # the most that lag was on a cycle's first acknowledgement, s
        self._wall = wall
        self._cond = threading.Condition()
        self._acknowledged = True
        self._in_step = True
        self._cycle_s = float('-inf')

    def published(self, cycle_s):
        """The simulator published the cycle at simulated time ``cycle_s``."""
        with self._cond:
            self._in_step = self._acknowledged      # the next acknowledgement is of this cycle
            self._acknowledged = False
            self._cycle_s = cycle_s

    def acknowledged(self, stamp_s):
        """A consumer took in a state stamped ``stamp_s`` (simulated s): the
        newest cycle's if the cycle before was acknowledged, else only if the
        stamp is of this cycle (a late acknowledgement must not let the
        simulator run a cycle further ahead)."""
        with self._cond:
            self.heard = True
            self.lag_s = self._cycle_s - stamp_s
            if not self._acknowledged:
                self.worst_lag_s = max(self.worst_lag_s, self.lag_s)
            if self._in_step or stamp_s >= self._cycle_s - STAMP_SLACK_S:
                self._in_step = False
                self._acknowledged = True
                self._cond.notify_all()

    def wait(self, consumers):
        """Block until the newest cycle is acknowledged, ``consumers()`` is
        false (nobody consumes: nothing to wait for) or ``bound_s`` of wall
        time passed. True when acknowledged or nobody consumes. Before the
        first acknowledgement nobody waits: a consumer starting up is not
        yet subscribed all along the chain."""
        end = self._wall() + self.bound_s
        with self._cond:
            while not self._acknowledged and self.heard and consumers():
                left = end - self._wall()
                if left <= 0:
                    self.overruns += 1
                    return False
                self._cond.wait(min(left, 0.05))   # re-ask consumers(): a dead one drops out
            return True
