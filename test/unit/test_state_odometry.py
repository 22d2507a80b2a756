"""The robot's odometry: the median of the drive boards (pirate.state.odometry).

test/data/odometry/straight_90_clamp_drive_300.csv was recorded with
``python3 bench/sim_twin_odometry 300 --record FILE`` (the twin, straight_90,
upright: Clamp Straight, then Drive 300 mm; per Mega cycle the raw odometry
count of each drive board and the true travel of the robot's middle). In
it Bend I's wheel (board 22, once the only odometry board) is propped
off the floor by the front module's shell and counts what the robot did
not travel.
"""
import csv
import math
import os

import pytest

from pirate.robot import tables
from pirate.state.odometry import WheelOdometry

RECORDED = os.path.join(os.path.dirname(__file__), '..', 'data', 'odometry', 'straight_90_clamp_drive_300.csv')
MM_PER_COUNT = 0.083


def recorded(phase):
    with open(RECORDED) as stream:
        return [row for row in csv.DictReader(stream) if row['phase'] == phase]


def fused_and_true(rows):
    odometry = WheelOdometry()
    for row in rows:
        for board in tables.DRIVE_BOARDS:
            odometry.update(board, int(row['odometry_%d' % board]))
        odometry.fold()
    return odometry.mm, float(rows[-1]['true_mm']) - float(rows[0]['true_mm'])


def board_mm(rows, board):
    key = 'odometry_%d' % board
    return (int(rows[-1][key]) - int(rows[0][key])) * MM_PER_COUNT


def test_recorded_clamp_the_propped_wheel_does_not_become_the_travel():
    rows = recorded('clamp')
    fused, true = fused_and_true(rows)
    assert abs(board_mm(rows, 22) - true) > 15.0          # board 22 alone: -27.6 mm for -5.5 mm
    assert fused == pytest.approx(true, abs=10.0)


def test_recorded_drive_is_the_travel_within_one_and_a_half_percent():
    rows = recorded('drive')
    fused, true = fused_and_true(rows)
    assert true > 250.0
    assert fused == pytest.approx(true, rel=0.015)


def cycles(odometry, steps, boards=tables.DRIVE_BOARDS):
    """Feed cycles of per-board raw counts (a dict board -> list of counts)."""
    for k in range(len(next(iter(steps.values())))):
        for board in boards:
            if board in steps and steps[board][k] is not None:
                odometry.update(board, steps[board][k])
        odometry.fold()


def test_two_wheels_spinning_free_and_a_dead_encoder_are_outvoted():
    odometry = WheelOdometry()
    rolling = [100 * k for k in range(6)]               # 100 counts per cycle
    cycles(odometry, {22: [250 * k for k in range(6)], 23: rolling, 24: rolling, 25: rolling,
                      26: [0] * 6, 27: [300 * k for k in range(6)]})
    assert odometry.mm == pytest.approx(500 * MM_PER_COUNT)


def test_a_board_that_did_not_report_does_not_vote():
    odometry = WheelOdometry()
    steps = {b: [100 * k for k in range(4)] for b in tables.DRIVE_BOARDS}
    steps[22] = [0, None, None, 900]                    # silent two cycles, then its whole count at once
    cycles(odometry, steps)
    assert odometry.mm == pytest.approx(300 * MM_PER_COUNT)


def test_each_board_unwraps_across_the_int16_wrap_backwards_too():
    odometry = WheelOdometry()
    forward = [32000, 32700, -32700, -32000, 32700]      # +700, +136, +700, -836
    cycles(odometry, {b: forward for b in tables.DRIVE_BOARDS})
    assert odometry.mm == pytest.approx(700 * MM_PER_COUNT)


def test_nothing_heard_is_zero_travel():
    odometry = WheelOdometry()
    odometry.fold()
    assert odometry.mm == 0.0 and not math.isnan(odometry.mm)


def test_each_part_is_fused_from_its_own_three_wheels():
    """Lying on a side with the rear V open, the rear rests on its shells and
    its three wheels spin free (twin: measurements.md#twin-odometry):
    the median of six then lies between the parts; each part's own median is its wheels' travel."""
    odometry = WheelOdometry()
    rolling, spinning = [40 * k for k in range(6)], [100 * k for k in range(6)]
    cycles(odometry, {22: rolling, 23: rolling, 24: [30 * k for k in range(6)], 25: spinning, 26: spinning,
                      27: spinning})
    assert odometry.part_mm('front') == pytest.approx(200 * MM_PER_COUNT)
    assert odometry.part_mm('rear') == pytest.approx(500 * MM_PER_COUNT)
    assert odometry.mm == pytest.approx(350 * MM_PER_COUNT)


def test_a_part_votes_only_with_the_boards_that_reported():
    odometry = WheelOdometry()
    steps = {b: [100 * k for k in range(4)] for b in tables.DRIVE_BOARDS}
    steps[25] = [0, None, None, None]                  # the rear rotational board silent
    steps[26] = [0, 300, 600, 900]                     # the rear apex wheel spinning free
    cycles(odometry, steps)
    assert odometry.part_mm('rear') == pytest.approx((300 + 100) / 2 * 3 * MM_PER_COUNT)
    assert odometry.part_mm('front') == pytest.approx(300 * MM_PER_COUNT)


def test_a_fold_waits_for_most_boards_so_a_split_cycle_counts_once():
    """A cycle's replies split over two folds (the end of the cycle heard
    before two delayed replies) counted the cycle twice: each part's median
    was the cycle's travel, and a drive read about twice its travel."""
    odometry = WheelOdometry()
    for board in tables.DRIVE_BOARDS:
        odometry.update(board, 0)
    for cycle in range(1, 11):
        early, late = tables.DRIVE_BOARDS[:4], tables.DRIVE_BOARDS[4:]
        for board in early:
            odometry.update(board, 100 * cycle)
        odometry.fold()                         # the end of the cycle, two replies still on their way
        for board in late:
            odometry.update(board, 100 * cycle)
            assert not odometry.fold()          # two boards alone never fold
    assert odometry.mm == pytest.approx(1000 * MM_PER_COUNT)
