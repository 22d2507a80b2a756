"""The sideways guard rows of config/guards_<mm>.yaml derived again from the
geometry (issue 10.2/10.3: derived, not measured; the report gives none).

Lying on a side the robot rests on its round shells (radius r), its axis r
above the floor, R - r below the pipe's axis, where the horizontal chord is
2 sqrt(R^2 - (R - r)^2). The V lies in that horizontal plane and spans the
chord when sin(beta) = (chord - D_w) / l (eq 2.1 with the chord for the
diameter): the wall angles are outer -2 beta, inner beta; the guards stop
0.05 rad short of them. The front tilt swings the front module (length l)
toward a wall; its tip, r off its axis, meets the wall at half the chord:
sin(theta) = (chord / 2 - r) / l; the lift guard stops 0.03 rad short.

110 mm non-nominal rows (issue 10.3, the report has none): a custom clamp
must hold down to lying on a side, so each is the sideways guard; the first
lift (on a side) is the report's 90 mm one scaled by the ratio of the two
diameters' theta; the later lift the 90 mm one scaled by the nominal lifts'
ratio (Table 5.3: 0.7 / 0.4).
"""
import math

import pytest

from pirate.sequencer import clamp_state as cs
from pirate.sequencer.guards import GuardBook, load_files

L_M, WHEEL_D_M = 0.09, 0.046      # report 2.4.1.1: l, D_w
SHELL_R_M = 0.020                 # config/twin.yaml geometry.body_radius_m (an estimate)
BOOK = GuardBook(*load_files())


def chord_m(diameter_m):
    radius = diameter_m / 2
    return 2 * math.sqrt(radius ** 2 - (radius - SHELL_R_M) ** 2)


@pytest.mark.parametrize('mm', [90, 110])
def test_sideways_clamp_guards_are_the_chord_s_wall_angles_less_the_margin(mm):
    beta = math.asin((chord_m(mm / 1000.0) - WHEEL_D_M) / L_M)
    pair = BOOK.for_diameter(mm).pair('clamp_sideways', 'rear')
    assert pair.outer.guard == pytest.approx(-2 * beta + 0.05, abs=0.01)
    assert pair.inner.guard == pytest.approx(beta - 0.05, abs=0.01)
    upright = BOOK.for_diameter(mm).pair('clamp', 'rear')      # on a side the V closes less than upright
    assert upright.outer.guard < pair.outer.guard and upright.inner.guard > pair.inner.guard


@pytest.mark.parametrize('mm', [90, 110])
def test_sideways_lift_guard_keeps_the_front_module_off_the_wall(mm):
    theta = math.asin((chord_m(mm / 1000.0) / 2 - SHELL_R_M) / L_M)
    guard = BOOK.for_diameter(mm).move('move_front_sideways').guard
    assert guard == pytest.approx(theta - 0.03, abs=0.01)


@pytest.mark.parametrize('roll, row', [(0.0, 'clamp_sideways'), (math.pi, 'clamp_sideways'),
                                       (-0.15, 'clamp_sideways'), (2 * math.pi - 0.1, 'clamp_sideways'),
                                       (0.3, 'clamp'), (math.pi / 2, 'clamp'), (None, 'clamp')])
def test_the_full_clamp_row_follows_the_roll(roll, row):
    assert cs.full_row(BOOK.for_diameter(90), roll) == row


def test_110_mm_non_nominal_rows_are_derived_from_the_90_mm_ones_and_the_geometry():
    g90, g110 = BOOK.for_diameter(90), BOOK.for_diameter(110)
    sideways = g110.pair('clamp_sideways', 'rear')
    for row in ('clamp_front_custom_first', 'clamp_front_custom', 'clamp_rear_custom'):
        pair = g110.pair(row, 'front' if 'front' in row else 'rear')
        assert (pair.outer.guard, pair.inner.guard) == (sideways.outer.guard, sideways.inner.guard)
    theta = {mm: math.asin((chord_m(mm / 1000.0) / 2 - SHELL_R_M) / L_M) for mm in (90, 110)}
    first = g90.move('move_front_first').guard * theta[110] / theta[90]
    later = g90.move('move_front_later').guard * g110.move('move_front').guard / g90.move('move_front').guard
    assert g110.move('move_front_first').guard == pytest.approx(first, abs=0.01)
    assert g110.move('move_front_later').guard == pytest.approx(later, abs=0.01)


def test_90_mm_front_custom_rows_on_a_side_are_the_chord_s():
    """The report measured its front custom clamps 0.7 rad off a side; on the
    side itself the V spans the chord, so the custom guard is clamp_sideways'."""
    g90 = BOOK.for_diameter(90)
    sideways = g90.pair('clamp_sideways', 'front')
    for row in ('clamp_front_custom_first', 'clamp_front_custom'):
        pair = g90.pair(row + cs.SIDEWAYS, 'front')
        assert (pair.outer.guard, pair.inner.guard) == (sideways.outer.guard, sideways.inner.guard)
        assert pair.outer.guard > g90.pair(row, 'front').outer.guard      # opener than the report's off-side row
        assert cs.row_at(g90, row, math.pi - 0.05) == row + cs.SIDEWAYS
        assert cs.row_at(g90, row, math.pi - 0.7) == row
