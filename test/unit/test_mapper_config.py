"""The panel YAML: every channel of SPEC 5 maps to its function and modes."""
import os
import re

import pytest
import yaml

from pirate.robot import tables
from pirate.msg import PirateGoal
from pirate.panel import config as panel_config

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
CONFIG = os.path.join(ROOT, 'config', 'nanokontrol2.yaml')

# SPEC 5, transcribed independently of the YAML: channel -> (action, target, modes).
M, P = 'manual', 'pab'
SPEC5 = {
    0: ('none', None, ()),
    1: ('setpoint', 'bend_iv', (M,)), 2: ('setpoint', 'bend_iii', (M,)),
    3: ('setpoint', 'bend_ii', (M,)), 4: ('setpoint', 'bend_i', (M,)),
    5: ('setpoint', 'front_tilt', (M,)), 6: ('setpoint', 'camera_tilt', (M, P)),
    7: ('setpoint', 'wheels', (M,)),
    16: ('setpoint', 'rear_led', (M, P)),
    17: ('limit', 'bend_iv', (M,)), 18: ('limit', 'bend_iii', (M,)),
    19: ('limit', 'bend_ii', (M,)), 20: ('limit', 'bend_i', (M,)),
    21: ('setpoint', 'camera_pan', (M, P)), 22: ('setpoint', 'front_led', (M, P)),
    23: ('setpoint', 'rotation', (M,)),
    32: ('mark_finding', None, (M, P)),     # unused in Table E.1 (no rear module control): marks a finding
    33: ('control_mode', 'bend_iv', (M,)), 34: ('control_mode', 'bend_iii', (M,)),
    35: ('control_mode', 'bend_ii', (M,)), 36: ('control_mode', 'bend_i', (M,)),
    37: ('control_mode', 'front_tilt', (M,)), 38: ('control_mode', 'camera_tilt', (M, P)),
    39: ('control_mode', 'wheels', (M,)),
    41: ('play', None, (M, P)), 42: ('stop', None, (M, P)),
    43: ('operation_mode', None, (M, P)), 45: ('no_limits_all', None, (M,)),
    49: ('single_stop', 'bend_iv', (M,)), 50: ('single_stop', 'bend_iii', (M,)),
    51: ('single_stop', 'bend_ii', (M,)), 52: ('single_stop', 'bend_i', (M,)),
    53: ('single_stop', 'front_tilt', (M,)), 54: ('single_stop', 'camera_tilt', (M,)),
    55: ('single_stop', 'wheels', (M,)),
    58: ('pab', None, (P,)), 59: ('pab', None, (P,)), 60: ('set_modifier', None, (M,)),
    65: ('calibrate', 'bend_iv', (M,)), 66: ('calibrate', 'bend_iii', (M,)),
    67: ('calibrate', 'bend_ii', (M,)), 68: ('calibrate', 'bend_i', (M,)),
    69: ('calibrate', 'front_tilt', (M,)), 70: ('calibrate', 'camera_tilt', (M,)),
}
# Free in Table E.2, PAB buttons here (every PAB from the panel).
SPEC5.update({channel: ('pab', None, (P,)) for channel in (44, 46, 48, 61, 62, 64, 71)})


@pytest.fixture(scope='module')
def cfg():
    return panel_config.load(CONFIG)


@pytest.mark.parametrize('channel', sorted(SPEC5))
def test_channel_matches_spec5(cfg, channel):
    entry = cfg.channels[channel]
    action, target, modes = SPEC5[channel]
    assert (entry.action, entry.target, tuple(entry.modes)) == (action, target, modes)
    assert entry.control and entry.function   # labelled for the operator


def test_no_other_channels(cfg):
    assert set(cfg.channels) == set(SPEC5)


def test_s_buttons_toggle_pwm_and_the_joints_other_mode(cfg):
    for channel in range(33, 40):
        entry = cfg.channels[channel]
        assert entry.off_mode == 'pwm'
        assert entry.on_mode in tables.element(entry.target).modes and entry.on_mode != 'pwm'


@pytest.mark.parametrize('channel,mode,value,counts', [
    (1, 'pwm', 127, 256), (2, 'torque', 127, -256), (6, 'pwm', 0, 252),
    (6, 'position', 0, 441), (21, 'position', 127, -448), (7, 'velocity', 0, -63),
    (23, 'position', 0, 4032), (16, 'pwm', 127, -254), (17, 'limit', 100, 200),
    (17, 'limit', 127, 0xFFFF), (5, 'position', 127, 448)])
def test_scaling_per_joint(cfg, channel, mode, value, counts):
    assert panel_config.scaled(cfg.channels[channel], mode, value) == counts


def test_magnitudes_are_those_of_spec3(cfg):
    gains = {e.channel: {m: abs(s.gain) for m, s in e.scale.items()} for e in cfg.channels.values()}
    for ch in (1, 2, 3, 4):
        assert gains[ch] == {'pwm': 4, 'torque': 4}
    assert gains[6]['position'] == gains[21]['position'] == 7
    assert gains[7]['velocity'] == 1 and gains[23]['position'] == 64
    assert gains[16]['pwm'] == gains[22]['pwm'] == 2


def test_pab_goals_use_the_action_codes(cfg):
    text = open(os.path.join(ROOT, 'action', 'Pirate.action')).read()
    codes = {k: int(v) for k, v in re.findall(r'uint8 (\w+) = (\d+)', text)}
    goal = cfg.channels[59].goal
    assert (goal.name, goal.option) == (codes['CLAMP_STRAIGHT'], codes['NONE'])
    goal = cfg.channels[44].goal
    assert (goal.name, goal.option) == (codes['T_JOINT'], codes['STRAIGHT'])
    assert cfg.channels[58].goal.name == codes['HOME'] and cfg.channels[62].goal.name == codes['DRIVE']


def test_every_pab_of_the_action_has_a_button(cfg):
    """Every PAB of Pirate.action, with each option it takes, is on the panel."""
    codes = {name: getattr(PirateGoal, name) for name in ('CLAMP_STRAIGHT', 'CLAMP_SIDEWAYS', 'T_JOINT',
                                                          'MITRE_BEND', 'DRIVE', 'HOME', 'LEFT', 'RIGHT')}
    goals = {(e.goal.name, e.goal.option) for e in cfg.channels.values() if e.action == 'pab'}
    names = {name for name, _ in goals}
    assert {codes[n] for n in ('CLAMP_STRAIGHT', 'CLAMP_SIDEWAYS', 'T_JOINT', 'MITRE_BEND', 'DRIVE', 'HOME')} <= names
    for sided in ('CLAMP_SIDEWAYS', 'MITRE_BEND'):
        assert {(codes[sided], codes['LEFT']), (codes[sided], codes['RIGHT'])} <= goals


@pytest.mark.parametrize('goal,needle', [
    ({'pab': 'FLY'}, 'one of'),
    ({'pab': 'HOME', 'distance': 5}, 'takes no distance'),
    ({'pab': 'HOME', 'pipe_diameter': 90}, 'takes no pipe_diameter'),
    ({'pab': 'T_JOINT'}, 'option NONE'),
    ({'pab': 'CLAMP_STRAIGHT', 'option': 'LEFT'}, 'option LEFT'),
    ({'pab': 'DRIVE', 'speed': 100}, 'needs a distance'),
    ({'pab': 'DRIVE', 'distance': 50, 'speed': 400}, 'speed'),
    ({'pab': 'DRIVE', 'distance': 'far'}, 'numbers'),
])
def test_bad_pab_goals_fail_at_load(goal, needle):
    raw = {'channel': 59, 'action': 'pab', 'modes': ['pab'], 'goal': goal}
    with pytest.raises(panel_config.ConfigError) as err:
        panel_config.from_params({'channels': [raw]})
    assert needle in str(err.value) and '59' in str(err.value)


@pytest.mark.parametrize('change,needle', [
    ({'action': 'fly'}, 'unknown action'), ({'target': 'bend_v'}, 'no setpoint element'),
    ({'scale': {'velocity': {'gain': 1, 'centre': 63}}}, 'has no velocity mode'),
    ({'modes': ['auto']}, 'unknown operation modes'), ({'only while stopped': None}, 'unknown keys')])
def test_a_typo_fails_at_load_naming_the_entry(change, needle):
    raw = yaml.safe_load(open(CONFIG))
    entry = next(e for e in raw['channels'] if e['channel'] == 4)
    entry.update(change)
    with pytest.raises(panel_config.ConfigError, match=needle):
        panel_config.from_params(raw)


def test_duplicate_channel_fails():
    raw = yaml.safe_load(open(CONFIG))
    raw['channels'].append(dict(raw['channels'][3]))
    with pytest.raises(panel_config.ConfigError, match='mapped twice'):
        panel_config.from_params(raw)
