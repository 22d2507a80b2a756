"""One writer on the command topics.

The Mega obeys whatever array reaches it last, so a second publisher on
``/pirate/setpoint_array`` (a forgotten ``rostopic pub``, a second manager)
silently overrides the sequencer and the safe hold. The manager listens to
its own command topics; every message names its sender (the ROS caller id),
and any sender but the manager is a rogue: detected on its first message,
reported once per sender and topic, and remembered for ``refuse_s`` after its
last message so that no goal starts while it may still be writing.

Pure Python: the caller passes the sender and the time.
"""

#: Seconds after a rogue's last message during which goals are refused.
REFUSE_S = 2.0


class OneWriter(object):
    """Tells the owner's messages from anyone else's on the command topics."""

    def __init__(self, owner, refuse_s=REFUSE_S):
        self.owner = owner
        self.refuse_s = refuse_s
        self._last = {}             # (topic, sender) -> time of the newest message

    def heard(self, topic, sender, now):
        """One message on ``topic`` from ``sender``; a report the first time a rogue is heard."""
        if sender == self.owner:
            return None
        first = (topic, sender) not in self._last
        self._last[(topic, sender)] = now
        if first:
            return ('second writer on %s: %s (only %s may command the robot); '
                    'goal cancelled, robot held and stopped' % (topic, sender, self.owner))
        return None

    def rogues(self, now):
        """(topic, sender) pairs heard within ``refuse_s``."""
        return sorted(key for key, last in self._last.items() if now - last <= self.refuse_s)

    def refusal(self, now):
        """Reason to refuse a goal while a rogue may still be writing, or None."""
        active = self.rogues(now)
        if not active:
            return None
        return 'another node writes the command topics (%s): stop it first' % ', '.join(
            '%s on %s' % (sender, topic) for topic, sender in active)
