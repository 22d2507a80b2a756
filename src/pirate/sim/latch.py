"""What the PICO boards latch from the laptop's three arrays (SPEC 3).

Shared by every simulated robot end: the arrays pass the same rules as the
laptop's (pirate.robot.safety); PLAY, STOP and No Limits All act on their
change at the command index; a stopped board, a single stop or a calibrate
leaves its motor without drive. Pure: no ROS.
"""
from pirate.robot import safety, tables

CODE = safety.MODE_CODES
PLAY, STOP, NO_LIMITS_ALL = (safety.COMMAND_CODES[k] for k in ('play', 'stop', 'no_limits_all'))
SINGLE_STOP, CALIBRATE = safety.COMMAND_CODES['single_stop'], safety.COMMAND_CODES['calibrate']


class CommandLatch(object):
    """The boards' latched setpoints, modes, limits and run state."""

    def __init__(self):
        self.running = False          # PICO boards stopped until PLAY
        self.no_limits = False
        self.setpoints = [0] * tables.SETPOINT_SIZE
        self.modes = [CODE['pwm']] * tables.CONTROL_SIZE
        self.limits = [safety.NO_LIMIT] * tables.LIMIT_SIZE
        self._last_command = None

    # --- inputs ------------------------------------------------------------
    def command(self, setpoints, modes, limits):
        """Latch the arrays as the boards would take them; return refusals.

        Inputs pass the same rules as the laptop's (pirate.robot.safety): a control
        code that does not exist keeps the element's previous code, a setpoint
        beyond what a board takes is clamped. Commands at the command index
        act on their change (a toggle must not re-fire on every repeat).
        Returns the list of reasons for anything refused or clamped.
        """
        reasons = []
        modes = list(modes)
        for index, code in enumerate(modes):
            try:
                safety.check_control_code(index, code)
            except safety.Refused as refused:
                reasons.append(str(refused))
                modes[index] = self.modes[index]
        self.modes = modes
        self.setpoints = [self._board_setpoint(elem, value, reasons)
                          for elem, value in zip(tables.SETPOINT_ELEMENTS, setpoints)]
        self.limits = list(limits)
        command = self.modes[tables.element('rear_module').index]
        if command != self._last_command:
            if command == PLAY:
                self.running = True
            elif command == STOP:
                self.running = False
            elif command == NO_LIMITS_ALL:
                self.no_limits = not self.no_limits
            self._last_command = command
        return reasons

    def _board_setpoint(self, elem, value, reasons):
        mode = safety.CODE_NAMES.get(self.modes[elem.index], 'pwm') \
            if elem.index < tables.CONTROL_SIZE else 'pwm'
        try:
            counts, reason = safety.limit_setpoint(elem.name, mode, value)
        except safety.Refused as refused:
            reasons.append(str(refused))
            return self.setpoints[elem.index]
        if reason:
            reasons.append(reason)
        return counts

    def _mode(self, name):
        return self.modes[tables.element(name).index]

    def _drive(self, name):
        """Setpoint counts ``name``'s motor acts on; 0 when it may not move."""
        index = tables.element(name).index
        mode = self.modes[index] if index < tables.CONTROL_SIZE else CODE['pwm']
        if not self.running or mode in (SINGLE_STOP, CALIBRATE):
            return None
        return self.setpoints[index]

    def _torque_counts(self, name, counts):
        """Apply the bend's torque limit (Table 4.3) unless No Limits All."""
        limit = self.limits[tables.limit_index(name)]
        if self.no_limits or limit == safety.NO_LIMIT:
            return counts
        return max(-limit, min(limit, counts))
