"""The Mega's watchdog, for every simulated robot end.

The firmware (``firmware/PirateBay/bridge.h``) drives the PICO boards only
while it is *armed*: a setpoint array arms it; no setpoint array for
``WATCHDOG_S`` disarms it, and a disarmed Mega sends every board STOP. So a
dead manager stops the real robot within the firmware's 300 ms budget; a
simulated robot must do the same, or tests see a robot that keeps moving.

Pure Python; the robot end passes its clock in (the wall clock, as on the
Mega, which knows nothing of simulated time) and asks :meth:`boards_see`
which control array the boards act on.
"""
from pirate.robot import safety, tables

#: firmware WATCHDOG_MS: 250 ms without a setpoint array, so that every
#: board is stopped within the 300 ms budget (bridge.h).
WATCHDOG_S = 0.25
COMMAND_INDEX = tables.element('rear_module').index


class MegaWatchdog(object):
    """Armed by each setpoint array; trips after ``timeout_s`` without one."""

    def __init__(self, timeout_s=WATCHDOG_S):
        self.timeout_s = timeout_s
        self.armed = False          # after power-up the boards get STOP
        self.trips = 0
        self._last = None

    def setpoint_arrived(self, now):
        """A valid setpoint array reached the Mega at ``now`` (s)."""
        self._last = now
        self.armed = True

    def poll(self, now):
        """Disarm when the setpoint stream stopped; True on the trip itself."""
        if self.armed and now - self._last > self.timeout_s:
            self.armed = False
            self.trips += 1
            return True
        return False

    def boards_see(self, modes):
        """The control array as the boards act on it: STOP while disarmed."""
        modes = list(modes)
        if not self.armed:
            modes[COMMAND_INDEX] = safety.COMMAND_CODES['stop']
        return modes
