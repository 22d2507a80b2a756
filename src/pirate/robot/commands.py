"""Setpoint, Control and Limit: the three arrays sent to the robot (report 4.2-4.4).

One instance of each lives in the pirate_manager process and is shared by
every writer (Mapper, Pirate Server, motion primitives), so a mode switch
never resets a setpoint (report 3.3). Every write passes through
:mod:`pirate.robot.safety`; nothing else checks limits.

Publishing policy (report 4.6):
- setpoints and limits are *marked* by writers and sent by :meth:`tick`,
  which the owner calls at 10 Hz, so slider bursts never exceed 10 Hz and the
  Mega's watchdog sees a steady stream while the robot is playing;
- control modes and commands go out at once, on every change; control and
  limits again whenever the device's link returns, and every second while
  it streams (:mod:`pirate.robot.link_watch`);
- :meth:`CommandArray.publish_now` bypasses the 10 Hz pacing, for the safe
  hold only (cancel must reach the wire fast).

Order on the wire: Setpoint and Control share one re-entrant
``wire_lock``; a copy is taken and published under it, so the wire sees the
arrays in the order their values were written, whichever thread writes.
The safe hold (:mod:`pirate.robot.hold`) takes the same lock for its whole
write, and a PAB writes under it only while its goal is not cancelled
(:meth:`pirate.sequencer.primitives.MotionPrimitives.writing`): nothing a
cancelled PAB had in flight can land on the wire after the hold.

Pure Python: the ROS publisher and the clock are passed in.
"""
import contextlib
import math
import threading
import time

from pirate.robot import safety, tables, units


class CommandArray(object):
    """A fixed-size command array with thread-safe get/set and paced publish."""

    size = 0

    def __init__(self, publisher, make_msg, clock=time.monotonic, log=None, wire_lock=None):
        self.wire_lock = wire_lock or threading.RLock()
        self._publisher = publisher
        self._make_msg = make_msg
        self._clock = clock
        self._log = log or (lambda text: None)
        self._values = [0] * self.size
        self._lock = threading.Lock()
        self._logged = set()
        self.published = 0

    def get_all(self):
        """All elements, as a list (a copy)."""
        with self._lock:
            return list(self._values)

    def _warn_once(self, reason):
        """Log a refusal once per distinct reason, so a burst logs once."""
        if reason and reason not in self._logged:
            self._logged.add(reason)
            self._log(reason)

    @contextlib.contextmanager
    def _logging_refusals(self):
        """Log a refusal once per reason, then let it reach the caller."""
        try:
            yield
        except safety.Refused as refused:
            self._warn_once(str(refused))
            raise

    def _check_size(self, values):
        """Refuse (and log once) a whole array of the wrong length."""
        with self._logging_refusals():
            if len(values) != self.size:
                raise safety.Refused('%s array needs %d values, got %d'
                                     % (type(self).__name__.lower(), self.size, len(values)))

    def _send(self):
        with self.wire_lock:
            with self._lock:
                msg = self._make_msg(list(self._values))
            self._publisher.publish(msg)
            self.published += 1
        return msg

    def publish_now(self):
        """Send the array immediately (control changes, safe hold)."""
        return self._send()


class Setpoint(CommandArray):
    """The 13-element setpoint array (Table 4.1), limited per control mode."""

    size = tables.SETPOINT_SIZE

    def __init__(self, publisher, make_msg, control, **kwargs):
        kwargs.setdefault('wire_lock', control.wire_lock)
        super(Setpoint, self).__init__(publisher, make_msg, **kwargs)
        self._control = control
        self.enabled = False
        #: ``measured() -> {joint: rad}`` (or None): what Play puts in
        #: position-mode elements; set by the owner that reads the robot.
        self.measured = lambda: None

    def set(self, name, value):
        """Write element ``name``; return the counts actually stored.

        Out-of-range values are clamped (and the reason logged once); a value
        that is not a finite number raises :class:`pirate.robot.safety.Refused`.
        """
        elem = tables.element(name)
        with self._logging_refusals():
            counts, reason = safety.limit_setpoint(name, self._control.mode_of(name), value)
        self._warn_once(reason)
        with self._lock:
            self._values[elem.index] = counts
        return counts

    def set_by_board(self, board, motor, value):
        """Write the element of PICO ``board`` / ``motor`` (report Fig A.1)."""
        return self.set(tables.SETPOINT_ELEMENTS[tables.index_of(board, motor)].name, value)

    def get(self, name):
        """Current counts of element ``name``."""
        with self._lock:
            return self._values[tables.element(name).index]

    def set_all(self, values):
        """Write the whole array (13 values), each through the limits."""
        self._check_size(values)
        for elem, value in zip(tables.SETPOINT_ELEMENTS, values):
            self.set(elem.name, value)

    def tick(self):
        """10 Hz pacing: send the array while enabled (after Play)."""
        if self.enabled:
            return self._send()
        return None


class Control(CommandArray):
    """The 12-element control-mode array (Table 4.2); changes go out at once."""

    size = tables.CONTROL_SIZE

    def set_mode(self, name, mode):
        """Put element ``name`` in ``mode`` ('pwm', 'torque', ...); publish if changed."""
        index = tables.element(name).index
        with self._logging_refusals():
            if mode not in safety.MODE_CODES:
                raise safety.Refused('unknown control mode %r (known: %s)'
                                     % (mode, sorted(safety.MODE_CODES)))
        return self.set_code(index, safety.MODE_CODES[mode])

    def set_code(self, index, code):
        """Write a raw mode/command code at ``index``; publish at once if changed."""
        with self._logging_refusals():
            safety.check_control_code(index, code)
        with self.wire_lock:
            with self._lock:
                changed = self._values[index] != code
                self._values[index] = code
            if changed:
                self._send()
        return changed

    def command(self, name):
        """Send a command at the command index: 'play', 'stop', 'no_limits_all'."""
        return self.set_code(tables.element('rear_module').index, safety.COMMAND_CODES[name])

    def mode_of(self, name):
        """The mode name element ``name`` is in ('pwm' for commands/unknown)."""
        index = tables.element(name).index
        if index >= self.size:
            return 'pwm'  # rear LED: no control mode, PWM only
        with self._lock:
            code = self._values[index]
        mode = safety.CODE_NAMES.get(code, 'pwm')
        return mode if mode in safety.MODE_CODES else 'pwm'

    def get(self, index):
        """Raw code at ``index``."""
        with self._lock:
            return self._values[index]

    def set_all(self, codes):
        """Write all 12 codes (each checked); publish once if anything changed."""
        self._check_size(codes)
        with self._logging_refusals():
            for index, code in enumerate(codes):
                safety.check_control_code(index, code)
        with self.wire_lock:
            with self._lock:
                changed = self._values != list(codes)
                self._values = list(codes)
            if changed:
                self._send()
        return changed


class Limit(CommandArray):
    """The 4-element torque-limit array (Table 4.3); uint16, 0xFFFF = none."""

    size = tables.LIMIT_SIZE

    def __init__(self, publisher, make_msg, **kwargs):
        super(Limit, self).__init__(publisher, make_msg, **kwargs)
        self._values = [safety.NO_LIMIT] * self.size
        self.enabled = False

    def set(self, name, value):
        """Write the torque limit of bend ``name``; return the stored value."""
        with self._logging_refusals():
            counts, reason = safety.limit_torque_limit(name, value)
        self._warn_once(reason)
        with self._lock:
            self._values[tables.limit_index(name)] = counts
        return counts

    def get(self, name):
        """Current torque limit of bend ``name``."""
        with self._lock:
            return self._values[tables.limit_index(name)]

    def set_all(self, values):
        """Write all four limits."""
        self._check_size(values)
        for name, value in zip(tables.LIMIT_ELEMENTS, values):
            self.set(name, value)

    def tick(self):
        """10 Hz pacing: send the limits while enabled (after Play)."""
        if self.enabled:
            return self._send()
        return None


def play(control, setpoint, limit):
    """Start the robot: PLAY to the boards and the 10 Hz setpoint/limit stream.

    Used by the Mapper's Play button and by the Pirate Server when a goal
    starts (a goal is a request to move). Play never moves anything by
    itself: every position-mode joint with an angle sensor gets
    its measured angle as setpoint first (a stored target, e.g. rotation 0,
    would turn it), and keeps it until someone writes a new one.
    """
    with control.wire_lock:
        hold_measured(control, setpoint, setpoint.measured())
        control.command('play')
        setpoint.enabled = limit.enabled = True


#: The LEDs that light the pipe for the cameras (report 2.4.1): front and rear.
LEDS = ('front_led', 'rear_led')


def lights_duty(duty):
    """``duty`` (PWM counts, 0 to DUTY_MAX) as the LEDs' setpoint; ValueError saying why not."""
    if isinstance(duty, bool) or not isinstance(duty, int) or not 0 <= duty <= safety.DUTY_MAX:
        raise ValueError('LED duty %r: a whole number of counts from 0 to %d' % (duty, safety.DUTY_MAX))
    return duty


def light(control, setpoint, duty):
    """Both LEDs at ``duty`` (:func:`lights_duty`); the safe hold leaves them so."""
    with control.wire_lock:
        for led in LEDS:
            setpoint.set(led, lights_duty(duty))


def playing(control):
    """The boards were last sent PLAY (not STOP): they run their setpoints."""
    return control.get(tables.element('rear_module').index) == safety.COMMAND_CODES['play']


#: The front camera's joints in the order :func:`point_camera` takes them.
CAMERA_JOINTS = ('camera_pan', 'camera_tilt')


def point_camera(control, setpoint, pan_rad, tilt_rad):
    """The front camera to ``pan_rad`` and ``tilt_rad`` in position mode, as
    the panel's pan knob and tilt slider in position mode send it;
    ValueError (nothing sent) for an angle that is not a number or lies
    beyond what the joint's encoder can tell (half a turn either way)."""
    counts = []
    for joint, rad in zip(CAMERA_JOINTS, (pan_rad, tilt_rad)):
        if isinstance(rad, bool) or not isinstance(rad, (int, float)) or not math.isfinite(rad):
            raise ValueError('%s %r: an angle in rad' % (joint, rad))
        value = units.rad_to_encoder(rad)
        if abs(value) > safety.POSITION_MAX_COUNTS:
            raise ValueError('%s %.2f rad: beyond half a turn either way, what its encoder tells' % (joint, rad))
        counts.append(value)
    with control.wire_lock:
        for joint, value in zip(CAMERA_JOINTS, counts):
            control.set_mode(joint, 'position')
            setpoint.set(joint, value)


def hold_measured(control, setpoint, angles):
    """Setpoint = measured angle for every position-mode joint that has a sensor."""
    elements = {e.name for e in tables.SETPOINT_ELEMENTS}
    for joint in tables.JOINTS:
        rad = (angles or {}).get(joint.name)
        if joint.board is None or joint.name not in elements or rad is None:
            continue
        if control.mode_of(joint.name) != 'position':
            continue
        if joint.angle_unit == tables.ROTATION:
            if safety.rotation_ok(rad):     # beyond the limit: a bad reading, keep the target
                setpoint.set(joint.name, units.rad_to_rotation(rad))
        else:
            setpoint.set(joint.name, units.rad_to_encoder(rad))
