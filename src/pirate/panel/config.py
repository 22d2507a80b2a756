"""The panel's channel map, read from YAML/params and checked before use.

A typo in the map (an unknown action, a target that is no setpoint element,
a scale for a mode the motor does not have) fails when the map is loaded,
with the entry named, not when the operator touches the control on the
robot. Pure Python: the map comes in as the dict rosparam loaded (or
``yaml.safe_load`` of the file, for tests).
"""
import collections

from pirate.panel import mission_buttons
from pirate.robot import safety, tables, units
from pirate.sequencer import goals

MANUAL, PAB = 'manual', 'pab'
OPERATION_MODES = (MANUAL, PAB)

#: What a channel can do; the Mapper has one handler per action.
BUTTON_ACTIONS = ('control_mode', 'single_stop', 'play', 'stop', 'operation_mode',
                  'no_limits_all', 'set_modifier', 'calibrate', 'pab', 'mark_finding')
CONTINUOUS_ACTIONS = ('setpoint', 'limit')
ACTIONS = ('none',) + CONTINUOUS_ACTIONS + BUTTON_ACTIONS
#: Actions whose target is a setpoint element / a bend with a torque limit.
_ELEMENT_TARGET = ('setpoint', 'control_mode', 'single_stop', 'calibrate')
MIDI_MAX = 127

#: One scaling rule: counts = gain * (centre - value).
Scale = collections.namedtuple('Scale', 'gain centre')
#: One checked channel entry (see config/nanokontrol2.yaml for the fields).
Entry = collections.namedtuple(
    'Entry', 'channel control function action modes target scale full_scale '
             'on_mode off_mode goal')
#: A PAB button's goal: code (Pirate.action name), distance mm, speed mm/s, option
#: code. No pipe diameter: every panel goal uses the launch's ``pipe_diameter``.
Goal = collections.namedtuple('Goal', 'name distance speed option')
#: ``mission_buttons``: channel -> pirate.panel.mission_buttons.MissionButton,
#: the PAB-mode job of buttons that act only in manual mode in ``channels``.
PanelConfig = collections.namedtuple(
    'PanelConfig', 'name press_threshold burst_max_per_s initial_modes channels mission_buttons')


class ConfigError(ValueError):
    """The panel map is inconsistent; the message names the entry."""


def _entry(raw):
    where = 'panel map entry %r' % (raw,)
    if not isinstance(raw, dict) or 'channel' not in raw:
        raise ConfigError('%s: needs at least channel and action' % where)
    unknown = set(raw) - set(Entry._fields)
    if unknown:
        raise ConfigError('%s: unknown keys %s (a comma inside an unquoted value?)'
                          % (where, sorted(unknown)))
    action = raw.get('action')
    if action not in ACTIONS:
        raise ConfigError('%s: unknown action %r (known: %s)' % (where, action, ', '.join(ACTIONS)))
    modes = tuple(raw.get('modes', ()))
    bad = [m for m in modes if m not in OPERATION_MODES]
    if bad:
        raise ConfigError('%s: unknown operation modes %s' % (where, bad))
    target = raw.get('target')
    if action in _ELEMENT_TARGET:
        try:
            element = tables.element(target)
        except KeyError as err:
            raise ConfigError('%s: %s' % (where, err))
    if action == 'limit':
        try:
            tables.limit_index(target)
        except KeyError as err:
            raise ConfigError('%s: %s' % (where, err))
    scale = {}
    for mode, rule in (raw.get('scale') or {}).items():
        if action == 'setpoint' and mode not in element.modes:
            raise ConfigError('%s: %s has no %s mode (modes: %s)' % (where, target, mode, element.modes))
        scale[mode] = Scale(float(rule['gain']), float(rule['centre']))
    if action in CONTINUOUS_ACTIONS and not scale:
        raise ConfigError('%s: a %s channel needs a scale' % (where, action))
    on_mode, off_mode = raw.get('on_mode'), raw.get('off_mode')
    if action == 'control_mode':
        for mode in (on_mode, off_mode):
            if mode not in element.modes:
                raise ConfigError('%s: %s has no %r mode (modes: %s)' % (where, target, mode, element.modes))
    goal = _goal(where, raw.get('goal')) if action == 'pab' else None
    full_scale = raw.get('full_scale')
    return Entry(int(raw['channel']), str(raw.get('control', '')), str(raw.get('function', '')),
                 action, modes, target, scale,
                 None if full_scale is None else int(full_scale), on_mode, off_mode, goal)


def _goal(where, raw):
    """The :data:`Goal` of a pab entry, ``{pab: NAME, distance, speed, option}``."""
    if not isinstance(raw, dict) or str(raw.get('pab', '')).upper() not in goals.CODES:
        raise ConfigError('%s: a pab channel needs goal {pab: one of %s}'
                          % (where, ', '.join(sorted(goals.CODES))))
    pab = str(raw['pab']).upper()
    allowed = ('pab', 'option') + goals.PAB_FIELDS.get(pab, ())
    unknown = sorted(set(raw) - set(allowed))
    if unknown:
        raise ConfigError('%s: %s takes no %s' % (where, pab, ', '.join(unknown)))
    option = str(raw.get('option', 'NONE')).upper()
    if option not in goals.PAB_OPTIONS.get(pab, ('NONE',)):
        raise ConfigError('%s: option %s for %s (allowed: %s)' % (
            where, option, pab, ' / '.join(goals.PAB_OPTIONS.get(pab, ('NONE',)))))
    try:
        distance, speed = float(raw.get('distance', 0.0)), float(raw.get('speed', 0.0))
    except (TypeError, ValueError):
        raise ConfigError('%s: distance and speed must be numbers' % where)
    if pab == 'DRIVE' and (abs(distance) < units.WHEEL_MM_PER_COUNT or not 0 <= speed <= safety.DRIVE_MAX_MM_S):
        raise ConfigError('%s: DRIVE needs a distance (mm, signed, at least the odometry\'s resolution %g) and a '
                          'speed in [0, %g] mm/s' % (where, units.WHEEL_MM_PER_COUNT, safety.DRIVE_MAX_MM_S))
    return Goal(goals.CODES[pab], distance, speed, goals.OPTIONS[option])


def from_params(params):
    """Build a checked :class:`PanelConfig` from the loaded YAML/param dict."""
    if not isinstance(params, dict) or not params.get('channels'):
        raise ConfigError('panel map has no "channels" list (was the panel YAML loaded '
                          'as private params of the node?)')
    channels = {}
    for raw in params['channels']:
        entry = _entry(raw)
        if entry.channel in channels:
            raise ConfigError('channel %d is mapped twice' % entry.channel)
        channels[entry.channel] = entry
    initial = dict(params.get('initial_modes') or {})
    for name, mode in initial.items():
        if mode not in tables.element(name).modes or mode not in safety.MODE_CODES:
            raise ConfigError('initial_modes: %s has no %r mode' % (name, mode))
    return PanelConfig(str(params.get('panel_name', '')),
                       int(params.get('press_threshold', 64)),
                       float(params.get('burst_max_per_s', 500)),
                       initial, channels,
                       mission_buttons.from_params(params.get('mission_buttons'), channels, ConfigError))


def load(path):
    """Read and check a panel YAML file (tests, tools; nodes use params)."""
    import yaml
    with open(path) as stream:
        return from_params(yaml.safe_load(stream))


def scaled(entry, mode, value):
    """Counts for raw MIDI ``value`` on ``entry`` with its target in ``mode``.

    Returns None when the entry has no scale for ``mode`` (the caller tells
    the operator). ``full_scale`` replaces the top value (torque limit 127 =
    no limit, 0xFFFF).
    """
    if entry.full_scale is not None and value == MIDI_MAX:
        return entry.full_scale
    rule = entry.scale.get(mode)
    if rule is None:
        return None
    return int(round(rule.gain * (rule.centre - value)))


def pab_buttons(cfg):
    """What the operator can start from the panel, one line per PAB button in
    channel order: '<control>: <function>' (without its 'PAB ' prefix), marked when the Pirate Server does
    not take that goal yet (so the operator knows before pressing), then the
    PABs of Pirate.action no button starts."""
    lines, named = [], set()
    for entry in sorted(cfg.channels.values(), key=lambda e: e.channel):
        if entry.action != 'pab':
            continue
        pab, option = goals.CODE_NAMES[entry.goal.name], goals.OPTION_NAMES[entry.goal.option]
        named.add(pab)
        taken = goals.built(pab, option if option != 'NONE' else None)
        function = entry.function[4:] if entry.function.startswith('PAB ') else entry.function
        lines.append('%s: %s%s' % (entry.control, function, '' if taken else ' (not yet taken)'))
    missing = sorted(set(goals.CODES) - named)
    if missing:
        lines.append('no button: %s' % ', '.join(missing))
    return lines

