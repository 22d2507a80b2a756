"""The steering's wedge watch (pirate.sequencer.pabs.junction.Wedge): what the
robot senses (the median wheel speed, robot time) decides when the front part
rolls off aligned and when it is aligned again; the rows it reads are in
config/guards_<mm>.yaml ``turn``."""
import math

import pytest

from pirate.robot import units
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import junction as jn
from pirate.state.feed import RobotView

BOOK = GuardBook(*load_files())
SPEED_MM_S = 25.0
#: A Mega cycle, robot s: one view each.
CYCLE_S = 0.1


class Prims(object):
    """Records what the watch sends: rotation setpoints (counts) and the operator's text."""

    def __init__(self):
        self.rotation, self.told = [], []

    def move_module(self, joint, counts):
        assert joint == 'rotation', joint
        self.rotation.append(counts)


def views(speeds_mm_s, start_s=0.0):
    """One view per Mega cycle at each wheel speed."""
    return [RobotView({}, math.pi, 0.0, speed, start_s + k * CYCLE_S, {}) for k, speed in enumerate(speeds_mm_s)]


def watch(mm=110):
    prims = Prims()
    row = BOOK.for_diameter(mm).row('turn')
    return prims, jn.Wedge(prims, row, SPEED_MM_S, prims.told.append), row


def run(wedge, speeds):
    for view in views(speeds, run.t):
        wedge.check(view)
    run.t += len(speeds) * CYCLE_S


@pytest.fixture(autouse=True)
def clock():
    run.t = 0.0


def cycles(seconds):
    return int(round(seconds / CYCLE_S))


@pytest.mark.parametrize('mm', [90, 110])
def test_the_rows_say_how_long_how_slow_and_how_far(mm):
    row = BOOK.for_diameter(mm).row('turn')
    assert 0 < float(row['wedge_s']) < float(row['steer_base_s'])
    assert 0 < float(row['wedge_free_s'])
    assert 0 < float(row['wedge_fraction']) < 1
    assert 0 < float(row['wedge_rotation_rad']) <= 0.7          # within the rotation's safety limit


def test_wheels_at_the_set_speed_never_roll_the_front():
    prims, wedge, _ = watch()
    run(wedge, [SPEED_MM_S] * 600)
    assert prims.rotation == [] and not wedge.turned


def test_a_stand_shorter_than_wedge_s_is_not_a_wedge():
    prims, wedge, row = watch()
    short = cycles(float(row['wedge_s'])) - 2
    run(wedge, [SPEED_MM_S] * 10 + [0.0] * short + [SPEED_MM_S] * 10 + [0.0] * short)
    assert prims.rotation == []


def test_wheels_standing_wedge_s_roll_the_front_once_then_align_it_once_they_turn_again():
    prims, wedge, row = watch()
    rolled = units.rad_to_rotation(float(row['wedge_rotation_rad']))
    stand = cycles(float(row['wedge_s'])) + 2
    run(wedge, [SPEED_MM_S] * 10 + [0.0] * stand)
    assert prims.rotation == [rolled] and wedge.turned
    run(wedge, [0.0] * 100)                                   # still standing: no second command
    assert prims.rotation == [rolled]
    run(wedge, [SPEED_MM_S] * (cycles(float(row['wedge_free_s'])) + 2))
    assert prims.rotation == [rolled, units.rad_to_rotation(0.0)] and not wedge.turned
    assert prims.told == ['front wedged (1): rotation %.2f rad' % float(row['wedge_rotation_rad']),
                          'front free: rotation 0']


def test_a_second_wedge_rolls_the_front_again():
    prims, wedge, row = watch()
    stand = cycles(float(row['wedge_s'])) + 2
    run(wedge, [0.0] * stand + [SPEED_MM_S] * stand + [0.0] * stand)
    assert len(prims.rotation) == 3 and wedge.turned and wedge.times == 2


def test_creeping_below_the_fraction_counts_as_standing():
    prims, wedge, row = watch()
    creep = 0.9 * float(row['wedge_fraction']) * SPEED_MM_S
    run(wedge, [creep] * (cycles(float(row['wedge_s'])) + 2))
    assert wedge.turned


def test_a_burst_of_speed_shorter_than_wedge_free_s_while_rolled_does_not_align():
    prims, wedge, row = watch()
    stand, burst = cycles(float(row['wedge_s'])) + 2, cycles(float(row['wedge_free_s'])) - 2
    run(wedge, [0.0] * stand + [SPEED_MM_S] * burst + [0.0] * 5 + [SPEED_MM_S] * burst)
    assert wedge.turned and len(prims.rotation) == 1


@pytest.mark.parametrize('mm', [90, 110])
def test_aligning_again_waits_less_than_rolling(mm):
    """Freed, the front part goes back to aligned before it is deep in the new
    pipe, where its walls would hold it rolled (the align after the steering
    then timed out in the twin)."""
    row = BOOK.for_diameter(mm).row('turn')
    assert CYCLE_S < float(row['wedge_free_s']) < float(row['wedge_s'])
