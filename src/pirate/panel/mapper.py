"""The Mapper: panel events -> setpoints, control modes, limits, PAB goals.

Report 4.6 and 5.7: the Mapper translates every control of the operator
panel (SPEC 5, config/nanokontrol2.yaml) into writes on the shared Setpoint,
Control and Limit objects, and, in PAB mode, into goals for the Pirate
Server. It keeps the operation mode (MANUAL / PAB, SPEC 1) and the run state
(playing / stopped).

Rules it enforces (and why):
- buttons act on the press edge only: the panel repeats values and sends a
  release, and a toggle must not flip twice;
- nothing moves before Play: setpoint/limit publishing is enabled by Play,
  and setpoint controls are ignored while stopped (report F.2);
- Stop zeroes the setpoints of motors in PWM or velocity mode (0 = motor off;
  the bends' worm gears hold them) and sends them at once; torque and
  position setpoints are kept, because a 0 there would unclamp or move the
  robot (report 3.3). So Play after Stop never moves a joint by itself;
- the operation mode changes only while stopped, and a mode change never
  touches a setpoint (report 3.3);
- in PAB mode only the controls whose map entry lists ``pab`` work; the
  operator is told once per mode entry;
- the panel is the operator's authority: while it is stopped no goal from
  any client may move the robot (:meth:`goal_refusal`, asked by the Pirate
  Server), and Stop cancels whatever goal runs, in either mode;
- a refused PAB button and a PAB that did not succeed blink that button's
  LED (the hardware panel has no screen); every message goes to ``log``,
  which the ROS edge shows on the virtual panel;
- limits are not checked here: every write goes through pirate.robot.safety inside
  Setpoint / Limit;
- in PAB mode the map's ``mission_buttons`` talk to the mission executive
  (pirate.panel.mission_buttons); while a mission runs its steps are the
  only PABs (a PAB button confirms the step that waits for it, or is
  refused), Stop cancels the mission as well, and a panel that disconnects
  pauses it (:meth:`panel_connected`);
- after the robot reset or its link re-handshook (:meth:`robot_back`) the
  setpoints are at the safe hold and nothing the operator set before
  resumes: a slider or knob acts again when it moves (an event with the
  value it had before is not a movement) or after Play; the operator is
  told why it stopped.

Bad input (unknown channel, value outside 0-127 or not an integer, a burst
of events on one channel) is logged once per reason and ignored.

Pure Python: publishing LEDs, logging, the PAB client and the clock are
passed in, so every rule is unit-tested without ROS.
"""
import threading

from pirate.robot import commands, link_watch, safety, tables
from pirate.robot.hold import safe_hold
from pirate.panel import config as panel_config
from pirate.panel import manual_guard, mission_buttons
from pirate.panel.config import MANUAL, PAB

#: The control-array index where play / stop / no-limits-all travel (SPEC 3).
COMMAND_INDEX = tables.element('rear_module').index
#: LED toggles (10 Hz ticks) of one blink signal: three blinks in 0.6 s.
BLINK_TOGGLES = 6
#: Why a goal is refused while the panel is stopped.
STOPPED_REFUSAL = 'the operator panel is stopped: press Play on the panel first'
#: What the operator is told when the robot comes back (:meth:`Mapper.robot_back`).
ROBOT_BACK_TOLD = 'stopped: %s; press Play or move a control' % link_watch.BACK_REASON


class Mapper(object):
    """Translate MidiInput (channel, value) events for one panel map.

    ``config``: a :class:`pirate.panel.config.PanelConfig` (or the raw param
    dict). ``setpoint``/``control``/``limit``: the shared pirate.robot.commands
    objects. ``pab_client``: ``send_goal(goal) -> (accepted, message)`` with a
    :data:`pirate.panel.config.Goal`, ``cancel()``, ``is_active() -> bool``;
    it reports the end of a goal to :meth:`pab_result`.
    ``led(button, on)`` lights a panel LED; ``log(text)`` tells the operator;
    ``clock()`` returns seconds (monotonic), used for burst detection.
    ``mission``: ``command(text)`` to the mission executive, whose answer
    comes back through :meth:`mission_reply` (None: no mission executive).
    ``finding``: ``mark(note)`` to the inspection recorder, which tells the
    operator what it recorded (None: no recorder).
    """

    def __init__(self, config, setpoint, control, limit, pab_client, led, log, clock, mission=None,
                 finding=None):
        if not isinstance(config, panel_config.PanelConfig):
            config = panel_config.from_params(config)
        self._config = config
        self._setpoint = setpoint
        self._control = control
        self._limit = limit
        self._pab = pab_client
        self._led = led
        self._log = log
        self._clock = clock
        self._finding = finding
        self._lock = threading.RLock()
        self.operation_mode = MANUAL
        self.playing = False
        self._pressed = {}          # channel -> bool, for edge detection
        self._set_held = False
        self._logged = set()        # reasons logged once for the whole run
        self._told = set()          # operator hints, once per operation-mode entry
        self._leds = {}             # button -> bool last sent
        self._burst = {}            # channel -> [window start s, count]
        self._pab_channel = None    # the PAB button whose goal runs (its LED is on)
        self._sent_channel = None   # the PAB button of the last goal sent (its result may come late)
        self._blinks = {}           # button -> LED toggles still to do
        self._ticks = 0             # 10 Hz ticks, the phase of the mission's blink
        self._settings = {}         # setpoint channel -> the value it last set
        self._unmoved = {}          # setpoint channel -> its value when the robot came back
        self.mission = mission_buttons.MissionPanel(config.mission_buttons, mission, log)
        self._pab_keys = {e.channel: mission_buttons.goal_key(e.goal)
                          for e in config.channels.values() if e.action == 'pab'}
        setpoint.enabled = False
        limit.enabled = False
        for name, mode in config.initial_modes.items():
            control.set_mode(name, mode)
        self._handlers = {
            'none': self._on_none, 'setpoint': self._on_setpoint, 'limit': self._on_limit,
            'control_mode': self._on_control_mode, 'single_stop': self._on_single_stop,
            'play': self._on_play, 'stop': self._on_stop,
            'operation_mode': self._on_operation_mode, 'no_limits_all': self._on_no_limits_all,
            'calibrate': self._on_calibrate, 'pab': self._on_pab, 'mark_finding': self._on_mark_finding,
        }
        self.refresh_leds(force=True)

    # --- input ---------------------------------------------------------------

    def handle(self, channel, value):
        """Act on one panel event; never raises on bad input."""
        with self._lock:
            if not _is_int(channel) or not _is_int(value):
                self._log_once(('type',), 'panel event (%r, %r) ignored: channel and value must '
                               'be integers' % (channel, value))
                return
            entry = self._config.channels.get(channel)
            if entry is None:
                self._log_once(('unknown', channel), 'channel %d is not on the panel map %r; '
                               'ignored' % (channel, self._config.name))
                return
            if not 0 <= value <= panel_config.MIDI_MAX:
                self._log_once(('range', channel), 'channel %d (%s): value %d outside 0-127; '
                               'ignored' % (channel, entry.control, value))
                return
            if entry.action != 'stop' and self._in_burst(entry):
                return
            button = self._config.mission_buttons.get(channel) if self.operation_mode == PAB else None
            if button is not None:
                if self._press_edge(channel, value):
                    self.mission.press(button)
                return
            if entry.action == 'set_modifier':
                self._set_held = value >= self._config.press_threshold
                self._set_led(channel, self._set_held)
                return
            if entry.action in panel_config.BUTTON_ACTIONS and not self._press_edge(channel, value):
                return
            if entry.action != 'none' and self.operation_mode not in entry.modes:
                self._tell_wrong_mode(entry)
                return
            self._handlers[entry.action](entry, value)

    def _press_edge(self, channel, value):
        """True only for the first pressed value after a release."""
        pressed = value >= self._config.press_threshold
        was = self._pressed.get(channel, False)
        self._pressed[channel] = pressed
        return pressed and not was

    def _in_burst(self, entry):
        """Count events per channel per second; True while over the limit."""
        now = self._clock()
        window = self._burst.setdefault(entry.channel, [now, 0])
        if now - window[0] >= 1.0:
            window[0], window[1] = now, 0
        window[1] += 1
        if window[1] > self._config.burst_max_per_s:
            self._log_once(('burst', entry.channel),
                           'channel %d (%s): more than %d events per second - a MIDI device '
                           'cannot send that many; ignoring it until it calms down'
                           % (entry.channel, entry.control, self._config.burst_max_per_s))
            return True
        return False

    # --- handlers --------------------------------------------------------------

    def _on_none(self, entry, value):
        self._log_once(('unused', entry.channel), 'channel %d (%s) is not used: %s'
                       % (entry.channel, entry.control, entry.function))

    def _on_mark_finding(self, entry, value):
        if self._finding is None:
            self._log('%s: no inspection recorder to mark a finding with' % entry.control)
            return
        self._finding.mark('marked from the panel (%s)' % entry.control)

    def _on_setpoint(self, entry, value):
        if not self.playing:
            self._tell('stopped', 'stopped: press Play before moving the robot')
            return
        if self._unmoved.get(entry.channel) == value:
            return      # the value from before the robot came back: not a movement
        mode = self._control.mode_of(entry.target)
        counts = panel_config.scaled(entry, mode, value)
        if counts is None:
            self._log_once(('no_scale', entry.channel, mode),
                           '%s (%s): no scaling for %s mode; ignored (change its control mode)'
                           % (entry.control, entry.function, mode))
            return
        self._setpoint.set(entry.target, counts)
        self._unmoved.pop(entry.channel, None)
        self._settings[entry.channel] = value

    def _on_limit(self, entry, value):
        self._limit.set(entry.target, panel_config.scaled(entry, 'limit', value))

    def _on_control_mode(self, entry, value):
        now_on = self._control.mode_of(entry.target) == entry.on_mode
        mode = entry.off_mode if now_on else entry.on_mode
        self._control.set_mode(entry.target, mode)
        # The setpoint is kept (report 3.3) but passed through the limits of
        # the new mode, so a value legal in one mode never goes out in another.
        self._setpoint.set(entry.target, self._setpoint.get(entry.target))
        self._set_led(entry.channel, mode == entry.on_mode)
        self._log('%s: %s mode' % (entry.target, mode))

    def _on_single_stop(self, entry, value):
        index = tables.element(entry.target).index
        self._control.set_code(index, safety.COMMAND_CODES['single_stop'])
        self._log('%s stopped (its S button selects a control mode again)' % entry.target)

    def manually_driven(self):
        """The motors the panel drives now in manual mode (pirate.panel.manual_guard):
        the wheels with a non-zero setpoint, a PWM joint with a non-zero setpoint;
        none while stopped, in PAB mode or while a PAB runs (its guards watch it)."""
        with self._lock:
            if not self.playing or self.operation_mode != MANUAL or self._pab.is_active():
                return []
            driven = [name for name in manual_guard.PWM_JOINTS
                      if self._control.mode_of(name) == 'pwm' and self._setpoint.get(name) != 0]
            if self._setpoint.get(manual_guard.WHEELS) != 0:
                driven.append(manual_guard.WHEELS)
            return driven

    def stop_stalled(self, motor, why):
        """Stop ``motor``, which the manual guard found driven without progress, and say why."""
        with self._lock:
            self._setpoint.set(motor, 0)     # the manager's next 10 Hz tick sends it
            self._log(why)

    def _on_play(self, entry, value):
        self.playing = True
        self._unmoved.clear()
        commands.play(self._control, self._setpoint, self._limit)
        self._run_leds()
        self._log('playing (%s mode)' % self.operation_mode)

    def _on_stop(self, entry, value):
        self.mission.stop()
        if self._pab.is_active():     # a PAB sent by any client, in either mode
            self._pab.cancel()
            self._log('Stop: the running PAB is cancelled')
        self._control.command('stop')
        self.safe_setpoints()
        self.playing = False
        self._setpoint.enabled = False
        self._limit.enabled = False
        self._run_leds()
        self._log('stopped')

    def _on_operation_mode(self, entry, value):
        if self.playing:
            self._log('operation mode not changed: press Stop first (modes change only '
                      'while stopped)')
            return
        self.operation_mode = PAB if self.operation_mode == MANUAL else MANUAL
        self._told.clear()
        self._set_led(entry.channel, self.operation_mode == PAB)
        self._log('operation mode: %s' % self.operation_mode.upper())

    def _on_no_limits_all(self, entry, value):
        if not self._set_held:
            self._tell('nla', 'hold Set (marker set) and press Record for No Limits All')
            return
        self._send_code(COMMAND_INDEX, safety.COMMAND_CODES['no_limits_all'])
        # A one-shot toggle: write the run command back so that a later
        # control-array message does not carry it again.
        self._control.command('play' if self.playing else 'stop')
        self._log('No Limits All toggled')

    def _on_calibrate(self, entry, value):
        if not self._set_held:
            self._tell('calibrate', 'hold Set (marker set) while pressing an R button to '
                       'calibrate that joint')
            return
        if not self.playing:
            self._tell('stopped', 'stopped: press Play before calibrating')
            return
        self._send_code(tables.element(entry.target).index, safety.COMMAND_CODES['calibrate'])
        self._log('%s: calibrating' % entry.target)

    def _on_pab(self, entry, value):
        if not self.playing:
            self._refuse(entry, 'press Play first')
            return
        if self.mission.is_waiting_step(self._pab_keys[entry.channel]):
            self.mission.send('confirm')
            return
        if self.mission.active:
            self._refuse(entry, 'a mission is running: its steps are its PABs (a blinking button '
                         'confirms the step that waits; Stop cancels the mission)')
            return
        if self._pab.is_active():
            self._refuse(entry, 'a PAB is running; wait for it or press Stop to cancel it')
            return
        accepted, message = self._pab.send_goal(entry.goal)
        if not accepted:
            self._refuse(entry, message)
            return
        self._log('%s: sent' % entry.function)
        self._pab_channel = self._sent_channel = entry.channel
        self._set_led(entry.channel, True)

    def _refuse(self, entry, reason):
        self._log('%s refused: %s' % (entry.function, reason))
        self._blinks[entry.channel] = BLINK_TOGGLES

    # --- authority and results ------------------------------------------------------

    def goal_refusal(self):
        """Why no goal may move the robot now (the panel is stopped), or None."""
        with self._lock:
            return None if self.playing else STOPPED_REFUSAL

    def pab_result(self, success, message, refused=False):
        """A goal the panel sent has ended: tell the operator; blink unless it succeeded."""
        with self._lock:
            self._log('%s: %s' % ('PAB refused' if refused else 'PAB ended', message))
            if not success and self._sent_channel is not None:
                self._blinks[self._sent_channel] = BLINK_TOGGLES
            self._sent_channel = None

    def robot_back(self):
        """The robot came back (a Mega reset, a re-handshake of its link) and
        its setpoints are at the safe hold (:func:`pirate.robot.link_watch.hold_and_restore`):
        the sliders' and knobs' values from before are not set again until
        they move or Play is pressed; tell the operator why it stopped."""
        with self._lock:
            self._unmoved = dict(self._settings)
            self._log(ROBOT_BACK_TOLD)

    # --- the mission executive's word (the ROS edge calls these) ---------------

    def mission_progress(self, feedback):
        """A mission feedback (step, level, what it waits for)."""
        with self._lock:
            self.mission.progress(feedback)

    def mission_ended(self, status, message):
        with self._lock:
            self.mission.ended(status, message)

    def mission_reply(self, command, ok, message):
        with self._lock:
            self.mission.reply(command, ok, message)

    def panel_connected(self, connected, reason):
        """The panel came or went (pirate.panel.presence). Gone while a
        mission runs: the mission pauses, holding the robot safe, because the
        operator has lost his Stop; it resumes only on the operator's word."""
        with self._lock:
            if connected:
                self._log('panel connected (%s)%s' % (reason, '; the mission stays paused until you '
                          'resume it' if self.mission.paused else ''))
                self.refresh_leds(force=True)
            else:
                self._log('panel disconnected: %s' % reason)
                self.mission.disconnected(reason)

    # --- outputs ---------------------------------------------------------------

    def safe_setpoints(self):
        """The safe hold (pirate.robot.hold), sent at once (Stop)."""
        safe_hold(self._setpoint, self._control)

    def _send_code(self, index, code):
        """Write a command code; send it again if it was already there."""
        if not self._control.set_code(index, code):
            self._control.publish_now()

    def _set_led(self, button, on, force=False):
        if force or self._leds.get(button) != on:
            self._leds[button] = on
            self._led(button, on)

    def _run_leds(self):
        for entry in self._config.channels.values():
            if entry.action == 'play':
                self._set_led(entry.channel, self.playing)
            elif entry.action == 'stop':
                self._set_led(entry.channel, not self.playing)

    def refresh_leds(self, force=False):
        """Bring every LED in line with the state (modes may be changed by a PAB).

        ``force`` sends every LED even if unchanged (a panel just connected).
        """
        with self._lock:
            wanted = {}
            for entry in self._config.channels.values():
                if entry.action == 'control_mode':
                    wanted[entry.channel] = self._control.mode_of(entry.target) == entry.on_mode
                elif entry.action == 'operation_mode':
                    wanted[entry.channel] = self.operation_mode == PAB
                elif entry.action == 'play':
                    wanted[entry.channel] = self.playing
                elif entry.action == 'stop':
                    wanted[entry.channel] = not self.playing
                elif entry.action == 'pab':
                    wanted[entry.channel] = entry.channel == self._pab_channel
                elif entry.action == 'set_modifier':
                    wanted[entry.channel] = self._set_held
            wanted.update(self._mission_leds())
            for channel, on in wanted.items():
                if channel not in self._blinks:
                    self._set_led(channel, on, force)

    def _mission_leds(self):
        """PAB mode: the mission buttons and the blinking waiting PAB; in
        manual mode the M buttons are immediate stops and stay dark."""
        if self.operation_mode != PAB:
            return {channel: False for channel in self._config.mission_buttons}
        return self.mission.leds(self._ticks, self._pab_keys)

    def tick(self):
        """Called at 10 Hz: follow the PAB state and the control modes on the LEDs."""
        with self._lock:
            if self._pab_channel is not None and not self._pab.is_active():
                self._pab_channel = None
            self._ticks += 1
            self._blink()
            self.refresh_leds()

    def _blink(self):
        """One step of every running blink signal; the LED returns to its state after."""
        for button, left in list(self._blinks.items()):
            if left <= 0:
                del self._blinks[button]
                continue
            self._set_led(button, left % 2 == 0)
            self._blinks[button] = left - 1

    # --- operator messages -------------------------------------------------------

    def _log_once(self, key, text):
        if key not in self._logged:
            self._logged.add(key)
            self._log(text)

    def _tell(self, key, text):
        """Tell the operator once per operation-mode entry."""
        if key not in self._told:
            self._told.add(key)
            self._log(text)

    def _tell_wrong_mode(self, entry):
        if self.operation_mode == PAB:
            self._tell('pab_joint', 'PAB mode: joint controls are ignored (%s); camera and '
                       'LEDs still work. Stop, then Rewind, for manual mode.' % entry.control)
        else:
            self._tell('manual_pab', 'manual mode: %s works only in PAB mode (Stop, then '
                       'Rewind)' % entry.control)


def _is_int(value):
    return isinstance(value, int) and not isinstance(value, bool)
