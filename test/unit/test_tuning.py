"""Tunables (dynamic_reconfigure, cfg/Sequencer.cfg) are checked and applied between goals."""
import math

import pytest

from pirate.state.feed import RobotFeed, RobotView
from pirate.sequencer import tuning
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import PirateServer

from fakes import command_arrays

WIDER = {'straight_low': 1.45, 'straight_high': 1.69, 'primitive_timeout': 20.0, 'feedback_timeout': 0.5}


@pytest.fixture
def server():
    _, setpoint, control, limit = command_arrays()
    feed = RobotFeed(0.3, clock=lambda: 10.0)
    feed.push(RobotView(dict.fromkeys(('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii',
                                       'bend_iv'), 0.0), math.pi / 2, 0.0, 0.0, 1.0))
    return PirateServer(MotionPrimitives(setpoint, control, limit, feed), feed,
                        GuardBook(*load_files()), lambda: None)


def test_defaults_are_the_config_files():
    config = pytest.importorskip('pirate.cfg.SequencerConfig')
    tables, common = load_files()
    assert tuning.current(common, RobotFeed(common['feedback_timeout'])) == config.defaults


def test_idle_server_applies_at_once(server):
    assert server.tune(WIDER) is None
    guards = server.book.for_diameter(90)
    assert guards.region('straight') == (1.45, 1.69)
    assert guards.primitive_timeout == 20.0 and server.feed.feedback_timeout == 0.5


def test_a_running_goal_keeps_its_settings_until_it_ends(server):
    server.active = 'CLAMP_STRAIGHT'            # as reserve() marks a running goal
    assert server.tune(WIDER) is None
    assert server.book.for_diameter(90).region('straight') == (1.52, 1.62)
    server.active = None
    server._finish(type('O', (), {'message': 'done'})())
    assert server.book.for_diameter(90).region('straight') == (1.45, 1.69)


@pytest.mark.parametrize('change,words', [
    ({'straight_low': 1.6, 'straight_high': 1.55}, 'below'),
    ({'straight_low': 1.3}, 'nominal'),
    ({'primitive_timeout': 0.0}, 'above 0'),
])
def test_bad_tunables_are_refused_and_change_nothing(server, change, words):
    values = dict(WIDER, **change)
    assert words in server.tune(values)
    assert server.book.for_diameter(90).region('straight') == (1.52, 1.62)
