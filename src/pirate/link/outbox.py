"""Latest value per outgoing topic, never a backlog.

rosserial_python queues every outgoing message without bound; after a stall
it replays all of them, so the robot executes stale setpoints. Here each
topic holds one slot: a newer message replaces the older one, and a message
that waited longer than ``max_age`` seconds is dropped rather than sent
(counted in ``stale_dropped``). Pure and thread-safe; time passed in.
"""
import threading


class Outbox(object):
    """One slot per key (the ROS topic name): (payload, time put)."""

    def __init__(self, max_age=0.2):
        self.max_age = max_age
        self.replaced = 0
        self.stale_dropped = 0
        self._slots = {}
        self._cond = threading.Condition()

    def put(self, key, payload, now):
        """Store ``payload`` as the latest for ``key`` and wake the writer."""
        with self._cond:
            if key in self._slots:
                self.replaced += 1
            self._slots[key] = (bytes(payload), now)
            self._cond.notify()

    def take(self, now):
        """Remove and return [(key, payload)] younger than max_age, oldest first."""
        with self._cond:
            items = sorted(self._slots.items(), key=lambda item: item[1][1])
            self._slots.clear()
        fresh = []
        for key, (payload, stamp) in items:
            if now - stamp > self.max_age:
                self.stale_dropped += 1
            else:
                fresh.append((key, payload))
        return fresh

    def clear(self):
        """Drop everything (link went down: nothing from before may be sent)."""
        with self._cond:
            self._slots.clear()

    def wait(self, timeout):
        """Block until something is put or ``timeout`` s pass; True if non-empty."""
        with self._cond:
            if not self._slots:
                self._cond.wait(timeout)
            return bool(self._slots)
