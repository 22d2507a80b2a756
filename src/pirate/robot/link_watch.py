"""Link watch: the laptop's command state back on the Mega whenever its link returns.

A Mega that reset has forgotten the control modes and torque limits and
holds the boards until both arrive again (firmware/README.md, "Safety").
Our serial_node re-sends latched values when the device announces itself
again; rosserial_python re-sends nothing, and the manager sends limits only
while playing. Whichever host runs, the device's Small State stream tells:
an unplug, a stall or a reset in its bootloader silences it, and its first
message after the silence is the link back; a reset too short to show (the
firmware restarted within a cycle) is covered by re-sending every
:data:`REFRESH_S` while the stream flows. The manager sends control and
limits at once, under the wire lock the setpoints take, so after a return
they reach the device before any setpoint. Re-sending them is harmless:
they are state, and the firmware keeps the newest. Pure: time passed in.
"""

#: s of Small State silence that count as the link gone: the Mega sends one
#: message per board, nine per 100 ms cycle (at most ~70 ms apart).
SILENCE_S = 0.15
#: s between two re-sends while the stream flows: a reset nobody saw gets
#: the laptop's state back within this.
REFRESH_S = 1.0


class LinkWatch(object):
    """When to send the laptop's state: the first Small State after a
    silence (``returns`` counts them), and every ``refresh_s`` besides."""

    def __init__(self, silence_s=SILENCE_S, refresh_s=REFRESH_S):
        self.silence_s = silence_s
        self.refresh_s = refresh_s
        self.returns = 0
        self._last = None
        self._sent = None

    def heard(self, now):
        """A Small State arrived at ``now`` (s); True if the state is to be
        sent: the link just came back (the first message ever, or the first
        after ``silence_s``), or ``refresh_s`` passed since it was sent."""
        back = self._last is None or now - self._last > self.silence_s
        self._last = now
        if back:
            self.returns += 1
        if back or now - self._sent >= self.refresh_s:
            self._sent = now
            return True
        return False


def restore(control, limit):
    """Send the control array, then the limits, at once and under the
    control's wire lock (no setpoint in between)."""
    with control.wire_lock:
        control.publish_now()
        limit.publish_now()
