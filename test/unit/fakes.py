"""Fakes shared by the unit tests (no ROS)."""


class Wire(object):
    """A publisher that records the arrays it was asked to send."""

    def __init__(self):
        self.sent = []

    def publish(self, data):
        self.sent.append(list(data))


def command_arrays():
    """Setpoint, Control and Limit over recording wires: (wires, setpoint, control, limit)."""
    from pirate.robot import commands
    wires = {k: Wire() for k in ('setpoint', 'control', 'limit')}
    control = commands.Control(wires['control'], list)
    setpoint = commands.Setpoint(wires['setpoint'], list, control)
    limit = commands.Limit(wires['limit'], list)
    return wires, setpoint, control, limit


class WithoutJunctionKey(object):
    """Guards (:class:`pirate.sequencer.guards.Guards`) whose ``junction`` row
    lacks ``key``: a guard file where that row was not measured."""

    def __init__(self, guards, key):
        self._guards, self._key = guards, key

    def row(self, name):
        row = self._guards.row(name)
        return {k: v for k, v in row.items() if k != self._key} if name == 'junction' else row

    def __getattr__(self, name):
        return getattr(self._guards, name)


class BookWithoutJunctionKey(object):
    """A guard book (:class:`pirate.sequencer.guards.GuardBook`) whose every
    diameter's ``junction`` row lacks ``key`` (:class:`WithoutJunctionKey`)."""

    def __init__(self, book, key):
        self._book, self._key = book, key

    def for_diameter(self, mm):
        return WithoutJunctionKey(self._book.for_diameter(mm), self._key)
