"""The operator launch's argument checker (pirate.launch_check), without roslaunch."""
import pytest

from pirate import launch_check

GOOD = {'robot': 'sim', 'world': 'straight_90', 'pipe_diameter': '90', 'panel': 'virtual', 'rviz': 'true',
        'record': 'false', 'rate': '1.0'}


def _with(**changes):
    args = dict(GOOD)
    args.update(changes)
    return args


def test_good_arguments_pass():
    assert launch_check.problems(GOOD) == []
    assert launch_check.main(['%s:=%s' % item for item in GOOD.items()]) == 0


@pytest.mark.parametrize('changes,words', [
    ({'rate': 'abc'}, 'rate:=abc: a real-time factor above 0 is needed'),
    ({'rate': '0'}, 'rate:=0: a real-time factor above 0'),
    ({'robot': 'real', 'rate': '2'}, 'the real robot runs in real time'),
    ({'robot': 'twin'}, 'robot:=twin: use sim or real'),
    ({'panel': 'keys'}, 'panel:=keys: use virtual or midi or none'),
    ({'pipe_diameter': '100'}, 'pipe_diameter:=100: use 90 or 110'),
    ({'record': 'yes'}, 'record:=yes: true or false'),
    ({'world': 'network90'}, 'world:=network90: no such world; the worlds there are: '),
    ({'world': 'straight_110'}, 'give pipe_diameter:=110'),
])
def test_a_bad_argument_is_named(changes, words):
    found = launch_check.problems(_with(**changes))
    assert len(found) == 1 and words in found[0], found


def test_a_wrong_world_lists_the_worlds(capsys):
    assert launch_check.main(['world:=netwrk_90', 'robot:=sim']) == 1
    err = capsys.readouterr().err
    assert 'network_90' in err and 'inspection_network_90' in err and 'straight_110' in err


def test_the_real_robot_needs_no_world():
    assert launch_check.problems(_with(robot='real', world='nowhere')) == []


def test_no_panel_is_said(capsys):
    assert launch_check.main(['panel:=none']) == 0
    assert 'no operator panel' in capsys.readouterr().err


def test_a_word_that_is_no_argument_is_refused(capsys):
    assert launch_check.main(['rate=2']) == 1
    assert "'rate=2'" in capsys.readouterr().err
