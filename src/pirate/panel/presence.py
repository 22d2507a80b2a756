"""Is the operator's panel there? Decided from what the ROS edge sees.

A panel is there while something publishes its events (the virtual panel,
the ``midi_input`` driver) and no driver says its device is gone (a USB
panel unplugged: ``midi_input`` lives on and says so on
``names.PANEL_DEVICE_TOPIC``). Only a loss after a panel was seen counts:
a stack run without a panel (a test, ``run_mission`` from a terminal) has
no panel to lose. Pure: the counts come in, the changes go out.
"""


class PanelPresence(object):
    """Follows the panel; :meth:`update` returns a change or None."""

    def __init__(self):
        self.seen = False
        self.connected = False
        self.device_ok = True          # no driver has said otherwise

    def device(self, ok):
        """A driver's word on its device (True = plugged in)."""
        self.device_ok = bool(ok)

    def update(self, publishers):
        """``publishers``: how many nodes publish panel events now.
        Returns ``(connected, reason)`` when that changed, else None."""
        now = publishers > 0 and self.device_ok
        if now == self.connected:
            return None
        self.connected = now
        if now:
            self.seen = True
            return True, 'a node publishes panel events'
        if not self.seen:
            return None
        if not self.device_ok:
            return False, 'the MIDI driver lost the panel device'
        return False, 'no node publishes panel events any more'
