"""Every limit on what goes to the robot, enforced in this one place.

The Setpoint, Control and Limit classes call these functions on every write,
whoever the writer is (the Mapper in manual mode, a motion primitive, the
safe hold), so no caller checks limits on its own. The rule for a value out
of range is: **clamp it to the nearest allowed value and report why**; a
value that cannot be clamped meaningfully (NaN, an unknown control-mode code)
is **dropped** and the previous value kept. The callers log the reason once.

Limits and where they come from:
- PWM and torque setpoints: -256..256 counts, the PICO's duty range
  (panel scaling 4*(63 - value) spans -256..252, SPEC 3).
- Wheel velocity: 170 mm/s, the robot's maximum drive speed (report 2.4.3.2,
  4.7.2); in PWM mode the duty range above.
- Rotation: +-0.7 rad from aligned (report 5.10.1), in rotation counts.
- Position setpoints of the camera and front module: half a turn of the
  AS5055 either way.
- Torque limits: uint16; 0xFFFF means no limit.
"""
import math

from pirate.robot import tables, units

DUTY_MAX = 256
DRIVE_MAX_MM_S = 170.0
ROTATION_MAX_RAD = 0.7
POSITION_MAX_COUNTS = 2048
NO_LIMIT = 0xFFFF

#: Control-mode codes (pirate/ControlArray.msg) a motor can be put in, and
#: the commands that travel in the control array (SPEC 3).
MODE_CODES = {'pwm': 0, 'velocity': 1, 'position': 2, 'torque': 3, 'current': 4}
COMMAND_CODES = {'calibrate': 5, 'torque_limit': 6, 'play': 7, 'stop': 8,
                 'no_limits_all': 9, 'single_stop': 10}
CODE_NAMES = {v: k for k, v in list(MODE_CODES.items()) + list(COMMAND_CODES.items())}


class Refused(ValueError):
    """A value that cannot be made safe by clamping; the old value stays."""


def _range(name, mode):
    """(low, high) in counts for setpoint element ``name`` in ``mode``."""
    if name == 'rotation':
        top = units.rad_to_rotation(ROTATION_MAX_RAD)
        return -top, top
    if name == 'wheels' and mode == 'velocity':
        top = units.mm_s_to_wheel_counts(DRIVE_MAX_MM_S)
        return -top, top
    if mode == 'position':
        return -POSITION_MAX_COUNTS, POSITION_MAX_COUNTS
    return -DUTY_MAX, DUTY_MAX


def _counts(name, what, value):
    """``value`` as whole counts; Refused when it is not a finite number."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise Refused('%s: %s %r is not a number' % (name, what, value))
    if not math.isfinite(number):
        raise Refused('%s: %s %r is not finite' % (name, what, value))
    return int(round(number))


def limit_setpoint(name, mode, value):
    """Return ``(counts, reason)``: ``value`` made safe for element ``name``.

    ``reason`` is None when the value was already within range. Raises
    :class:`Refused` for a value that is not a finite number.
    """
    tables.element(name)  # KeyError for an unknown element
    counts = _counts(name, 'setpoint', value)
    low, high = _range(name, mode)
    if counts < low or counts > high:
        clamped = min(max(counts, low), high)
        return clamped, ('%s: setpoint %d counts outside [%d, %d] in %s mode, '
                         'clamped to %d' % (name, counts, low, high, mode, clamped))
    return counts, None


def check_control_code(index, code):
    """Raise :class:`Refused` unless ``code`` is a known control-mode/command."""
    if not 0 <= index < tables.CONTROL_SIZE:
        raise Refused('control index %r outside 0..%d' % (index, tables.CONTROL_SIZE - 1))
    if code not in CODE_NAMES:
        raise Refused('control code %r at index %d is not a mode or command (known: %s)'
                      % (code, index, sorted(CODE_NAMES)))


def limit_torque_limit(name, value):
    """Return ``(uint16, reason)`` for a torque limit of bend ``name``."""
    tables.limit_index(name)
    counts = _counts(name, 'torque limit', value)
    if 0 <= counts <= NO_LIMIT:
        return counts, None
    clamped = min(max(counts, 0), NO_LIMIT)
    return clamped, '%s: torque limit %d outside 0..65535, clamped to %d' % (name, counts, clamped)


def drive_speed_ok(mm_s):
    """True when a requested drive speed (mm/s) is within the robot's maximum."""
    return math.isfinite(mm_s) and abs(mm_s) <= DRIVE_MAX_MM_S


def rotation_ok(rad):
    """True when a rotation target (rad from aligned) is within +-0.7 rad."""
    return math.isfinite(rad) and abs(rad) <= ROTATION_MAX_RAD + 1e-9
