"""doc/panel.md's table of controls is the one generated from the panel map."""
import os
import re

import pytest

from pirate.panel import config, doc_table

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
PANEL_DOC = os.path.join(ROOT, 'doc', 'panel.md')
BLOCK = re.compile(r'<!-- generated: panel-controls[^>]*-->\n(.*?)\n<!-- end generated[^>]*-->', re.S)


def _small_map(**extra):
    params = {'channels': [
        {'channel': 41, 'control': 'play', 'function': 'start', 'action': 'play', 'modes': ['manual', 'pab']},
        {'channel': 0, 'control': 'slider 1', 'function': 'rear module', 'action': 'none', 'modes': []},
        {'channel': 49, 'control': 'M 2', 'function': 'immediate stop Bend IV', 'action': 'single_stop',
         'target': 'bend_iv', 'modes': ['manual']},
        {'channel': 59, 'control': 'track >', 'function': 'PAB Clamp | Straight', 'action': 'pab',
         'modes': ['pab'], 'goal': {'pab': 'CLAMP_STRAIGHT'}},
    ]}
    params.update(extra)
    return params


def test_the_checked_in_table_is_the_generated_one():
    with open(PANEL_DOC) as stream:
        found = BLOCK.search(stream.read())
    assert found, 'doc/panel.md has no panel-controls block'
    assert found.group(1) == doc_table.generate(), \
        'doc/panel.md is out of date with config/nanokontrol2.yaml: run make docs'


def test_one_row_per_channel_in_channel_order():
    rows = doc_table.controls_table(_small_map()).splitlines()
    assert rows[:2] == doc_table.HEADER.splitlines()
    assert [row.split('|')[2].strip() for row in rows[2:]] == ['0', '41', '49', '59']


def test_each_mode_column_shows_the_job_there():
    rows = doc_table.controls_table(_small_map()).splitlines()
    assert rows[2] == '| slider 1 | 0 | not used | not used |'
    assert rows[3] == '| play | 41 | start | start |'
    assert rows[4] == '| M 2 | 49 | immediate stop Bend IV |  |'
    assert rows[5] == '| track > | 59 |  | PAB Clamp \\| Straight |'


def test_a_mission_button_shows_its_pab_mode_job():
    params = _small_map(mission_buttons=[
        {'channel': 49, 'control': 'M 2', 'command': 'confirm', 'function': 'confirm the step'}])
    row = doc_table.controls_table(params).splitlines()[4]
    assert row == '| M 2 | 49 | immediate stop Bend IV | mission: confirm the step |'


def test_a_bad_map_is_refused_with_the_entry_named():
    params = _small_map()
    params['channels'][0]['action'] = 'plya'
    with pytest.raises(config.ConfigError, match='plya'):
        doc_table.controls_table(params)
