"""The virtual panel lists every PAB button and says which the server does not take."""
import os

import pygame

from pirate import paths
from pirate.panel import config, virtual
from pirate.sequencer import goals

CFG = config.load(os.path.join(paths.CONFIG_DIR, 'nanokontrol2.yaml'))


def test_every_pab_of_the_action_is_on_the_list():
    lines = config.pab_buttons(CFG)
    pab_entries = [e for e in CFG.channels.values() if e.action == 'pab']
    assert len(lines) == len(pab_entries)       # every PAB code has a button: no 'no button' line
    assert {goals.CODE_NAMES[e.goal.name] for e in pab_entries} == set(goals.CODES)
    assert 'fast forward: Take T-joint straight on' in lines
    assert 'cycle: Take mitre bend left' in lines and 'M 1: Take mitre bend right' in lines   # taken now
    assert 'track >: Clamp Straight' in lines


def test_a_pab_without_a_button_is_named():
    channels = {c: e for c, e in CFG.channels.items() if not (e.action == 'pab' and e.goal.name == 5)}
    lines = config.pab_buttons(CFG._replace(channels=channels))
    assert lines[-1] == 'no button: HOME'


def test_the_panel_draws_the_list():
    os.environ.setdefault('SDL_VIDEODRIVER', 'dummy')
    panel = virtual.VirtualPanel()
    surface = pygame.Surface((virtual.WIDTH, virtual.HEIGHT), 0, virtual.DEPTH_BITS)
    panel.draw(surface)
    blank = pygame.image.tostring(surface, 'RGB')
    panel.pab_list = config.pab_buttons(CFG)
    panel.draw(surface)
    assert pygame.image.tostring(surface, 'RGB') != blank
    bottom = virtual.PAB_LIST_Y + 13 * ((len(panel.pab_list) + 1) // 2)
    assert bottom <= virtual.HEIGHT and virtual.PAB_LIST_X + virtual.PAB_LIST_COLUMN_W < 420   # left of the strips
