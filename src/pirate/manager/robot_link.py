"""What the manager does with each Small State and each announcement of
the device: the link watch composed with the goal that runs, the command
arrays and the panel (pure, time passed in; :mod:`pirate.robot.link_watch`
says when).

The link up, or a refresh: control and limits again. The robot back (a
Mega reset, a re-handshake of its link: a silence in Small State, or the
device announcing itself again to serial_node): nothing it did before
resumes unasked. A running goal ends, the setpoints go to the safe
hold before control and limits, and the panel drops the operator's
settings from before and says why the robot stopped
(:meth:`pirate.panel.mapper.Mapper.robot_back`).
"""
import threading

from pirate.robot import link_watch


class RobotLink(object):
    """``server``: ``active`` and ``cancel(reason)`` (the Pirate Server);
    ``measured() -> {joint: rad}`` or None; ``mapper() -> Mapper`` or None
    (no panel, or not composed yet); ``log(text)`` warns the log."""

    def __init__(self, setpoint, control, limit, server, measured, mapper, log):
        self.watch = link_watch.LinkWatch()
        self._setpoint, self._control, self._limit = setpoint, control, limit
        self._server = server
        self._measured = measured
        self._mapper = mapper
        self._log = log
        self._lock = threading.Lock()   # Small State and announcements come on two threads

    def heard(self, now):
        """A Small State at ``now`` (s); return what the link watch made of it."""
        with self._lock:
            what = self.watch.heard(now)
            if what == link_watch.BACK:
                self._hold()
            elif what:
                link_watch.restore(self._control, self._limit)
            return what

    def announced(self):
        """The device announced itself to serial_node; return BACK when that is the robot back."""
        with self._lock:
            what = self.watch.announced()
            if what == link_watch.BACK:
                self._hold()
            return what

    def _hold(self):
        self._log('%s: setpoints at the safe hold, control modes and limits sent again'
                  % link_watch.BACK_REASON)
        if self._server.active:
            self._server.cancel(link_watch.BACK_REASON)
        link_watch.hold_and_restore(self._setpoint, self._control, self._limit, self._measured())
        mapper = self._mapper()
        if mapper is not None:
            mapper.robot_back()
