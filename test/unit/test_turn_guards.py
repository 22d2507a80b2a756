"""The 110 mm turn rows of config/guards_110.yaml derived again from the 90 mm
ones (measured in the twin) and the geometry (derived, not
measured; checked in the twin by test_pab_junction_twin.py).

The angles of a turn are set by the 90 deg corner and the joints' stops,
not by the pipe, so they are the 90 mm ones, as are the torques and speeds
(the same robot). What depends on the diameter D: every sign that the
front is round the corner (``steered_rad``, ``steered_sum_rad``,
``corner_inner_rad``) must stay well above the largest angle a straight
pipe allows, where the Bend I module (length l) at Bend II's angle spans
the pipe less a wheel (l sin(beta) = D - D_w); ``drive_in_mm`` is the
corner's length (one diameter) plus 60 mm. The 110 mm T-joint's wider
corner needed ``steered_sum_rad``, a lower ``corner_inner_rad`` and a
longer ``timeout_s`` (checked in the twin: config/guards_110.yaml); the
slowest and fastest speeds a turn takes, ``goal_speed_min`` and
``goal_speed_max``, were measured there again.
"""
import math

import pytest

from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import turn_motions as motions
from pirate.state.feed import RobotView

L_M, WHEEL_D_M = 0.09, 0.046      # report 2.4.1.1: l, D_w
BOOK = GuardBook(*load_files())
DIAMETER_BOUND = ('steered_rad', 'steered_sum_rad', 'corner_inner_rad', 'drive_in_mm', 'timeout_s')
#: Measured in the twin in 110 mm as well, not derived: the slowest and fastest speeds a turn takes there,
#: and whether the front part is levelled before it steers.
MEASURED_110 = ('goal_speed_min', 'goal_speed_max', 'level_front')
#: How far above the straight-pipe bound each sign stays (rad).
MARGINS = {'steered_rad': 0.5, 'steered_sum_rad': 0.5, 'corner_inner_rad': 0.3}


def straight_pipe_bend_ii_rad(diameter_m):
    return math.asin((diameter_m - WHEEL_D_M) / L_M)


@pytest.mark.parametrize('mm', [90, 110])
def test_the_front_counts_round_the_corner_only_far_above_what_a_straight_pipe_allows(mm):
    row = BOOK.for_diameter(mm).row('turn')
    bound = straight_pipe_bend_ii_rad(mm / 1000.0)
    for key, margin in MARGINS.items():
        if key in row:
            assert float(row[key]) >= bound + margin, (key, row[key], bound)


@pytest.mark.parametrize('mm', [90, 110])
def test_the_rear_drives_one_diameter_and_60_mm_into_the_new_pipe(mm):
    assert float(BOOK.for_diameter(mm).row('turn')['drive_in_mm']) == pytest.approx(mm + 60.0)


def test_every_other_110_mm_turn_value_is_the_90_mm_one():
    g90, g110 = BOOK.for_diameter(90), BOOK.for_diameter(110)
    row90, row110 = g90.row('turn'), g110.row('turn')
    assert set(row110) == set(row90) | {'steered_sum_rad'}
    assert float(row110['timeout_s']) >= float(row90['timeout_s'])
    assert {k: v for k, v in row110.items() if k not in DIAMETER_BOUND + MEASURED_110} == \
        {k: v for k, v in row90.items() if k not in DIAMETER_BOUND + MEASURED_110}
    assert g110.move('move_front_turn') == g90.move('move_front_turn')


@pytest.mark.parametrize('bend_i, bend_ii, steered_90, steered_110', [
    (0.29, 1.43, True, True),        # a mitre bend: Bend II round the corner (twin, 90 mm)
    (0.67, 0.93, False, True),       # the 110 mm T-joint: Bend I takes part of the turn (twin)
    (-0.5, 0.79, False, False),      # the most a straight 110 mm pipe allows
])
def test_the_front_is_steered_on_bend_ii_or_in_110_mm_on_bend_i_and_ii(bend_i, bend_ii, steered_90, steered_110):
    view = RobotView(dict(bend_i=bend_i, bend_ii=bend_ii), math.pi, 0.0, 0.0, 1.0, {})
    assert motions.steered(BOOK.for_diameter(90).row('turn'), view) is steered_90
    assert motions.steered(BOOK.for_diameter(110).row('turn'), view) is steered_110
