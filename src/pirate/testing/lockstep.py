"""Robot time of an in-process simulated robot that runs in lockstep with the sequencer.

Software-in-the-loop as ArduPilot's and PX4's SITL run their controller
with the simulator: the robot advances one cycle only when every consumer
of its state has taken the last one and waits for the next, so a run is a
function of its inputs alone. A busy host slows it, never changes it; an
idle one runs it as fast as the CPU allows.

A consumer is a thread that waits through :meth:`Lockstep.wait` (the
feed's guard waits, a test waiting for robot time to pass): it counts while
it waits. Inside :meth:`Lockstep.taking_part` it counts between its waits
too, so the robot stands still while it works on a state (a goal's whole
run). With no consumer the robot stands still: robot time passes only while
someone waits for it.

The robot's turn (``turn``: one cycle, or an action between two) runs in
the robot's own thread (:meth:`Lockstep.robot_loop`), never in a
consumer's: a consumer waits holding its condition's lock, which a turn
taken in its thread would keep from every other thread (a cancel). A turn
ends with :meth:`Lockstep.advance` or :meth:`Lockstep.nudge`.

Pure Python, no ROS.
"""
import contextlib
import threading


class Lockstep(object):
    """Robot seconds (call it), advanced ``cycle_s`` a cycle from ``start_s``."""

    def __init__(self, start_s, cycle_s, turn):
        self._start_s, self._cycle_s = start_s, cycle_s
        self._turn = turn
        self._turning = False       # a thread takes the robot's turn now
        self._lock = threading.Condition()
        self._cycle = 0
        self._epoch = 0             # a new cycle, or something else every consumer must see
        self._waiting = {}          # thread id -> (condition it waits on, epoch it waits after)
        self._members = {}          # thread id -> depth of its taking_part blocks
        self._closed = False

    def __call__(self):
        return self._start_s + self._cycle * self._cycle_s

    @property
    def closed(self):
        """True once the robot stopped (:meth:`close`)."""
        return self._closed

    # --- consumers ---------------------------------------------------------
    @contextlib.contextmanager
    def taking_part(self):
        """The calling thread counts as a consumer for the block: the robot
        waits for it while it works between its waits."""
        me = threading.get_ident()
        with self._lock:
            self._members[me] = self._members.get(me, 0) + 1
        try:
            yield
        finally:
            with self._lock:
                self._members[me] -= 1
                if not self._members[me]:
                    del self._members[me]
                self._poke()

    def wait(self, cond, poll_s=None):
        """Wait on ``cond`` (held by the caller) until it is notified or the
        robot's next cycle; ``poll_s`` (wall s) only once the robot stopped."""
        if self._closed:
            cond.wait(poll_s)
            return
        me = threading.get_ident()
        with self._lock:
            self._waiting[me] = (cond, self._epoch)
            self._poke()
        try:
            cond.wait()
        finally:
            with self._lock:
                del self._waiting[me]
                self._poke()

    def _take_turn(self):
        """(lock held) True, and the turn marked taken, when the robot's turn is due."""
        if self._turning or self._closed or not self._ready():
            return False
        self._turning = True
        return True

    def _run_turn(self):
        try:
            self._turn()
        finally:
            with self._lock:
                self._turning = False
                self._poke()

    def _poke(self):
        """(lock held) Wake the robot's thread when its turn is due."""
        if not self._turning and self._ready():
            self._lock.notify_all()

    # --- the robot ---------------------------------------------------------
    def robot_loop(self):
        """The robot's thread: take every turn as it falls due, until closed."""
        while True:
            with self._lock:
                while not self._closed and not self._take_turn():
                    self._lock.wait()
                if self._closed:
                    return
            self._run_turn()

    def _ready(self):
        if not self._waiting:
            return False
        if any(self._waiting.get(member, (None, -1))[1] != self._epoch for member in self._members):
            return False
        return all(epoch == self._epoch for _, epoch in self._waiting.values())

    def advance(self):
        """One cycle of robot time passed (:meth:`wake` the consumers after its state)."""
        with self._lock:
            self._cycle += 1
            self._epoch += 1

    def nudge(self):
        """Something happened between two cycles (a cancel): the robot waits
        until every consumer has seen it and waits again."""
        with self._lock:
            self._epoch += 1
        self.wake()

    def wake(self):
        """Wake the consumers still waiting on an earlier epoch."""
        with self._lock:
            stale = [cond for cond, epoch in self._waiting.values() if epoch < self._epoch]
        for cond in stale:
            with cond:
                cond.notify_all()

    def close(self):
        """The robot stopped: no consumer waits for it any more."""
        with self._lock:
            self._closed = True
            self._lock.notify_all()
            waiting = [cond for cond, _ in self._waiting.values()]
        for cond in waiting:
            with cond:
                cond.notify_all()
