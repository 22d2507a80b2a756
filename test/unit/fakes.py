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
