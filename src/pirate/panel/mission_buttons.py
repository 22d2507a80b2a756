"""The panel's mission buttons: in PAB mode the M row speaks to the mission.

The operator sets the autonomy level, confirms a step
and pauses / resumes a mission from the panel. Every nanoKONTROL2 button
already has a job in PAB mode or in manual mode, so the map gives a button
a second action per operation mode: the M buttons stop single joints in
manual mode (SPEC 5) and do nothing in PAB mode, where a mission runs; the
``mission_buttons`` list of the panel YAML gives them their PAB-mode job
(config/nanokontrol2.yaml). A mission is a sequence of PABs, so PAB mode
is where its controls belong; no extra mode to remember.

What the operator sees: the level buttons light the level in force, the
pause button stays lit while the mission is paused, and while a step
waits for confirmation the confirm button and the button of the waiting
PAB (if the panel has one for that PAB, option and direction) blink;
pressing either confirms. While a mission runs every other PAB button is
refused (its goals come from the mission). Stop cancels the mission too,
also one on its way to the executive.

Pure Python: the mission client (``command(text)``, replies coming back
through :meth:`MissionPanel.reply`) is passed in.
"""
import collections

from pirate.sequencer import goals
from pirate.supervisory.executive import LEVELS, WAIT_CONFIRM, WAIT_RESUME

#: One PAB-mode mission button of the panel map.
MissionButton = collections.namedtuple('MissionButton', 'channel control function command')
#: The executive's words a button may send (pirate.supervisory.executive.Executive.command).
COMMANDS = ('confirm', 'pause', 'resume') + tuple('level %s' % level for level in LEVELS)
#: What a mission button reads on the virtual panel in PAB mode (one short word per command).
LABELS = {'confirm': 'confirm', 'pause': 'pause', 'resume': 'resume', 'level full': 'full',
          'level confirm': 'lvl conf', 'level manual': 'manual'}
#: 10 Hz ticks per half period of the continuous blink of a waiting step (2.5 Hz).
BLINK_HALF_TICKS = 2


def from_params(raw_list, channels, error):
    """Checked ``{channel: MissionButton}`` from the YAML list; ``error``
    is the exception class to raise with the entry named."""
    buttons = {}
    for raw in raw_list or ():
        where = 'mission button %r' % (raw,)
        if not isinstance(raw, dict) or set(raw) - set(MissionButton._fields) or 'channel' not in raw:
            raise error('%s: needs channel, control, function, command and nothing else' % where)
        channel, command = int(raw['channel']), str(raw.get('command', ''))
        if command not in COMMANDS:
            raise error('%s: unknown command %r (known: %s)' % (where, command, ', '.join(COMMANDS)))
        entry = channels.get(channel)
        if entry is None:
            raise error('%s: channel %d is not on the panel map (give it its manual-mode job, or '
                        'action none)' % (where, channel))
        if 'pab' in entry.modes:
            raise error('%s: channel %d already acts in PAB mode (%s)' % (where, channel, entry.function))
        if channel in buttons:
            raise error('%s: channel %d is a mission button twice' % (where, channel))
        buttons[channel] = MissionButton(channel, str(raw.get('control', '')), str(raw.get('function', '')),
                                         command)
    return buttons


class MissionPanel(object):
    """What the panel knows of the mission, and what its buttons do."""

    def __init__(self, buttons, client, log):
        self.buttons = buttons
        self._client, self._log = client, log
        self.active = False
        self.level = None                  # unknown until the executive says
        self.waiting_for = ''
        self._step = None                  # (pab, option, direction) of the step running or waiting

    # --- the executive's word ------------------------------------------------
    def progress(self, feedback):
        """A mission feedback (pirate/MissionFeedback or executive Progress)."""
        self.active = True
        self.level, self.waiting_for = feedback.level, feedback.waiting_for
        self._step = (feedback.pab, feedback.option or 'NONE', _direction(feedback.distance_mm))

    def ended(self, status, message):
        self.active, self.waiting_for, self._step = False, '', None
        self._log('mission %s: %s' % (status or 'ended', message))

    def reply(self, command, ok, message):
        """The executive's answer to a command the panel sent (the cancel of
        a Stop with no mission running says nothing worth telling)."""
        if command == 'cancel' and not self.active:
            return
        self._log('mission %s: %s' % (command, message) if ok else
                  'mission %s refused: %s' % (command, message))
        if ok and command.startswith('level '):
            self.level = command.split()[1]

    # --- the operator ----------------------------------------------------------
    def press(self, button):
        """A mission button was pressed (PAB mode)."""
        self.send(button.command)

    def send(self, command):
        if self._client is None:
            self._log('mission %s: no mission executive is connected to this panel' % command)
            return
        self._client.command(command)

    def stop(self):
        """Stop on the panel: the mission ends (Stop always cancels), also
        one sent that the executive has not taken in yet (it cancels a
        mission sent before the word, when it comes)."""
        if self._client is not None:
            self.send('cancel')

    def disconnected(self, reason):
        """The panel is gone: a running mission pauses, holding the robot safe."""
        if self.active and not self.paused:
            self._log('panel disconnected (%s): pausing the mission' % reason)
            self.send('pause the operator panel disconnected (%s)' % reason)

    @property
    def paused(self):
        return self.waiting_for.startswith(WAIT_RESUME)

    @property
    def confirming(self):
        return self.active and self.waiting_for.startswith(WAIT_CONFIRM)

    def is_waiting_step(self, goal_key):
        """True if ``goal_key`` (pab name, option, direction) is the step waiting for confirmation."""
        return self.confirming and goal_key == self._step

    # --- LEDs ----------------------------------------------------------------
    def leds(self, tick, pab_buttons):
        """``{button: on}`` for the mission buttons and, while a step waits
        for confirmation, the waiting PAB's buttons (``pab_buttons``:
        channel -> goal key). ``tick`` counts 10 Hz ticks (the blink phase)."""
        blink_on = (tick // BLINK_HALF_TICKS) % 2 == 0
        out = {}
        for channel, button in self.buttons.items():
            if button.command == 'confirm':
                out[channel] = self.confirming and blink_on
            elif button.command == 'pause':
                out[channel] = self.active and self.paused
            elif button.command.startswith('level '):
                out[channel] = self.level == button.command.split()[1]
            else:
                out[channel] = False
        for channel, key in pab_buttons.items():
            if self.is_waiting_step(key):
                out[channel] = blink_on
        return out


class ExecutiveWatch(object):
    """Is the mission executive still there? Its action server reports its
    status several times a second; a mission the panel believes active but
    not heard of for ``limit_s`` is lost (its node died), so the panel stops
    refusing PAB buttons for it rather than lock the operator out."""

    def __init__(self, limit_s):
        self.limit_s, self._heard = limit_s, None

    def heard(self, now_s):
        self._heard = now_s

    def lost(self, now_s, active):
        """True once for a mission that is active but silent too long."""
        if not active:
            self._heard = None
            return False
        if self._heard is None:
            self._heard = now_s          # active since now, as far as we know
        return now_s - self._heard > self.limit_s


def _direction(distance_mm):
    """Backwards (a reversing drive, a junction searched rear first) or
    not: a panel button without a distance goes forwards."""
    return -1 if distance_mm < 0 else 1


def labels(buttons):
    """``{channel: label}`` of the mission buttons (``{channel: MissionButton}``),
    for a panel that draws their PAB-mode job."""
    return {channel: LABELS[button.command] for channel, button in buttons.items()}


def goal_key(goal):
    """What identifies a panel :data:`pirate.panel.config.Goal` for the
    operator, as a mission step is named: PAB name, option name, direction."""
    return (goals.CODE_NAMES[goal.name], goals.OPTION_NAMES[goal.option], _direction(goal.distance))
