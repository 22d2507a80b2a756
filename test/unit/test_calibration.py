"""The fast fake (sim/fake_robot.py, unit tests only) still reproduces the
simple clamp straight it was fitted to (a fit, not a prediction).

Runs the scripted sequence of bench/sim_calibration (one source for the
sequence; the bench prints the figures, this test holds them to the report):
Table 6.1 duration 10.77 s (+-1.5 s) and Table 6.5 angles (outer -0.835,
inner 0.43 rad, +-0.1 rad). Simulated time only, so it is not a timing test.
"""
import importlib.machinery
import importlib.util
import os

import pytest

BENCH = os.path.join(os.path.dirname(__file__), '..', '..', 'bench', 'sim_calibration')


@pytest.fixture(scope='module')
def bench():
    loader = importlib.machinery.SourceFileLoader('sim_calibration', BENCH)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader(loader.name, loader))
    loader.exec_module(module)
    return module


@pytest.fixture(scope='module')
def result(bench):
    return bench.simple_clamp_straight(90)


def test_simple_clamp_straight_takes_the_reports_time(result):
    assert result['total_s'] == pytest.approx(10.8, abs=1.5)
    assert sum(result['steps'].values()) == pytest.approx(result['total_s'])


def test_simple_clamp_straight_ends_clamped_at_table_6_5_angles(result):
    assert result['clamped'] == (True, True)
    angles = result['angles']
    for outer in ('bend_i', 'bend_iv'):
        assert angles[outer] == pytest.approx(-0.835, abs=0.1)
    for inner in ('bend_ii', 'bend_iii'):
        assert angles[inner] == pytest.approx(0.43, abs=0.1)
    assert angles['front_tilt'] >= 0.4


def test_every_step_takes_time(result):
    # a step that ends on its first sample would mean the guard held before it moved
    assert all(seconds > 1.0 for seconds in result['steps'].values())


def test_110_mm_also_clamps(bench):
    assert bench.simple_clamp_straight(110)['clamped'] == (True, True)


def test_main_prints_the_figures(bench, capsys):
    assert bench.main(['sim_calibration']) == 0
    out = capsys.readouterr().out
    assert 'duration [s]' in out and '10.77' in out
