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
they are state, and the firmware keeps the newest.

The robot back (:data:`BACK`: the Mega reset, or the link was
re-negotiated) is more than a re-send. Our serial_node says so: the device
announces itself again (:meth:`LinkWatch.announced`), before its first
Small State. With another host only a silence of :data:`RESET_SILENCE_S`
tells it: a short silence is a stall or a late laptop, after which the
firmware's freshness gate lets the stream go on. Either way what the robot
was doing before must not resume unasked: :func:`hold_and_restore`
writes the safe hold into the setpoints before control and limits go out,
so the boards re-arm at the hold and stay there until the operator acts
again (the Mapper's :meth:`pirate.panel.mapper.Mapper.robot_back`).
Pure: time passed in.
"""
from pirate.robot.hold import safe_hold

#: s of Small State silence that count as the link gone: the Mega sends one
#: message per board, nine per 100 ms cycle (at most ~70 ms apart).
SILENCE_S = 0.15
#: s of silence that count as the robot back when it streams again: a
#: silence our serial_node takes for a lost link (its ``~sync_timeout``); a
#: Mega's reset runs its bootloader 1-2 s (pirate.link.session), a late manager
#: in lockstep with the simulated robot misses about a cycle (doc/clock.md).
RESET_SILENCE_S = 0.5
#: s between two re-sends while the stream flows: a reset nobody saw gets
#: the laptop's state back within this.
REFRESH_S = 1.0
#: What a Small State tells (:meth:`LinkWatch.heard`): the link up (the
#: first message, or the first after ``silence_s``); the robot back (after
#: ``reset_silence_s``: a reset, a re-handshake); a refresh while it streams.
UP, BACK, REFRESH = 'up', 'back', 'refresh'
#: Why a running goal ends when the link comes back.
BACK_REASON = 'the robot reset (link re-established)'


class LinkWatch(object):
    """When to send the laptop's state: the first Small State after a
    silence (``returns`` counts them), and every ``refresh_s`` besides."""

    def __init__(self, silence_s=SILENCE_S, refresh_s=REFRESH_S, reset_silence_s=RESET_SILENCE_S):
        self.silence_s = silence_s
        self.refresh_s = refresh_s
        self.reset_silence_s = reset_silence_s
        self.returns = 0
        self._last = None
        self._sent = None

    def heard(self, now):
        """A Small State arrived at ``now`` (s); what to send, or None:
        :data:`UP` (the first message ever, or the first after
        ``silence_s``), :data:`BACK` (the first after ``reset_silence_s``),
        :data:`REFRESH` (``refresh_s`` after the last send)."""
        silent_s = None if self._last is None else now - self._last
        self._last = now
        if silent_s is None or silent_s > self.silence_s:
            self.returns += 1
            self._sent = now
            return BACK if silent_s is not None and silent_s > self.reset_silence_s else UP
        if now - self._sent >= self.refresh_s:
            self._sent = now
            return REFRESH
        return None

    def announced(self):
        """The device announced itself to its host (the link up, a reset, a
        re-handshake): :data:`BACK` if it streamed before (it may have
        forgotten the laptop's state), else None. Its next Small State is
        the link up, not a second return."""
        streamed, self._last = self._last is not None, None
        return BACK if streamed else None


def restore(control, limit):
    """Send the control array, then the limits, at once and under the
    control's wire lock (no setpoint in between)."""
    with control.wire_lock:
        control.publish_now()
        limit.publish_now()


def hold_and_restore(setpoint, control, limit, angles=None):
    """The link is back: the safe hold (``angles``: joint rad by name, if
    known), then control and limits, all under the wire lock, so the boards
    re-arm at the hold, never at a setpoint from before."""
    with control.wire_lock:
        safe_hold(setpoint, control, angles)
        restore(control, limit)
