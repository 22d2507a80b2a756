"""Lockstep between a simulated robot and the stack (doc/clock.md).

The simulator owns simulated time (``/clock``). After it publishes a Mega
cycle's Small States it waits until the stack has consumed them - the
manager acknowledges each robot state it takes in - before it steps on.
So simulated time never runs more than one Mega cycle past the newest state
the manager holds, whatever the laptop's load: a descheduled consumer is
late, and its watchdogs, judging silence on simulated time, see no silence.

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


class Lockstep(object):
    """One Mega cycle at a time: published, then acknowledged (or the bound)."""

    def __init__(self, bound_s=WAIT_BOUND_S, wall=time.monotonic):
        if not bound_s > 0:
            raise ValueError('lockstep bound %r s: must be above 0' % (bound_s,))
        self.bound_s = bound_s
        self.overruns = 0           # cycles the simulator stepped on unacknowledged
        self.heard = False          # a consumer acknowledged a cycle (one is there and subscribed)
        self._wall = wall
        self._cond = threading.Condition()
        self._acknowledged = True

    def published(self):
        """The simulator published a cycle: acknowledgements before now were of earlier ones."""
        with self._cond:
            self._acknowledged = False

    def acknowledged(self):
        """A consumer took in the state of the newest cycle."""
        with self._cond:
            self._acknowledged = self.heard = True
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
