"""Drawn robots of a sweep (pirate.testing.drawn_robots): each case once per robot,
each robot drawn from the sweep seed and its number alone."""
import argparse

import pytest

from pirate.testing import drawn_robots
from pirate.sweep.cases import Sweep, SweepError, case

SWEEP = Sweep('fake', ('mm', 'robot'), lambda params, seed, settings: {})


def _cases():
    return [case(SWEEP, {'mm': mm}, '%d mm' % mm, 1) for mm in (90, 110)]


def test_without_robots_the_cases_stay_on_the_nominal_twin():
    args = argparse.Namespace(robots=0, seed=1)
    assert drawn_robots.over(_cases(), SWEEP, args) == _cases()
    assert drawn_robots.twin_args(_cases()[0]['params'], 5, drawn_robots.settings(args)) == {}


def test_every_case_runs_once_per_drawn_robot_in_its_own_row():
    args = argparse.Namespace(robots=3, seed=1)
    found = drawn_robots.over(_cases(), SWEEP, args)
    assert sorted(c['key'] for c in found) == sorted('mm=%d robot=%d' % (mm, k) for mm in (90, 110)
                                                     for k in (1, 2, 3))
    assert {c['group'] for c in found} == {'90 mm, drawn robots', '110 mm, drawn robots'}


def test_a_case_draws_its_robot_again_from_the_sweep_seed_and_its_number():
    settings = drawn_robots.settings(argparse.Namespace(robots=2, seed=4))
    first = drawn_robots.twin_args({'mm': 90, 'robot': 2}, 11, settings)
    assert first['seed'] == 11, "the case's seed turns the sensors' noise on"
    assert drawn_robots.twin_args({'mm': 110, 'robot': 2}, 12, settings)['config'] == first['config']
    assert drawn_robots.twin_args({'mm': 90, 'robot': 1}, 11, settings)['config'] != first['config']
    assert drawn_robots.constants(4, 2)[1] == first['config']


def test_a_negative_count_is_refused():
    with pytest.raises(SweepError, match='--robots -1'):
        drawn_robots.over(_cases(), SWEEP, argparse.Namespace(robots=-1, seed=1))
