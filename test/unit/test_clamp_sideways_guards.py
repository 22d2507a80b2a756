"""The sideways guard rows of config/guards_<mm>.yaml derived again from the
geometry (derived, not measured; the report gives none).

Lying on a side the robot rests on its round shells (radius r), its axis r
above the floor, R - r below the pipe's axis, where the horizontal chord is
2 sqrt(R^2 - (R - r)^2). The V lies in that horizontal plane and spans the
chord when sin(beta) = (chord - D_w) / l (eq 2.1 with the chord for the
diameter): the wall angles are outer -2 beta, inner beta; the guards stop
0.05 rad short of them. The front tilt swings the front module (length l)
toward a wall; its tip, r off its axis, meets the wall at half the chord:
sin(theta) = (chord / 2 - r) / l; the lift guard stops 0.03 rad short.
Rolled phi off the side, the chord through the axis is
2 sqrt(R^2 - ((R - r) cos phi)^2); the sideways clamp row holds (its
``within_rad``) until that chord lets the V reach the upright guards.

110 mm non-nominal rows (the report has none): a custom clamp
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


def chord_off_side_m(diameter_m, phi_rad):
    """The chord through the axis of a robot on its shells rolled ``phi_rad`` off a side."""
    radius = diameter_m / 2
    return 2 * math.sqrt(radius ** 2 - ((radius - SHELL_R_M) * math.cos(phi_rad)) ** 2)


@pytest.mark.parametrize('mm', [90, 110])
def test_the_sideways_clamp_row_holds_until_the_upright_guards_come_within_reach(mm):
    """within_rad is the roll off the side where the V's wall angles first lie
    0.05 rad past the upright clamp guards: closer to the side only the
    sideways row can be reached."""
    guards = BOOK.for_diameter(mm)
    upright = guards.pair('clamp', 'rear')
    beta_needed = max(-upright.outer.guard / 2, upright.inner.guard) + 0.05
    phi = math.acos(math.sqrt((mm / 2000.0) ** 2 - ((WHEEL_D_M + L_M * math.sin(beta_needed)) / 2) ** 2)
                    / (mm / 2000.0 - SHELL_R_M))
    within = float(guards.row('clamp_sideways')['within_rad'])
    assert within == pytest.approx(phi, abs=0.01)
    for off, reachable in ((within - 0.02, False), (within + 0.02, True)):
        beta = math.asin((chord_off_side_m(mm / 1000.0, off) - WHEEL_D_M) / L_M)
        assert (beta >= beta_needed) is reachable, (off, beta)
    assert within < math.pi / 2 - (guards.region('nominal')[1] - guards.region('nominal')[0]) / 2


@pytest.mark.parametrize('mm, roll, row', [
    (90, 0.0, 'clamp_sideways'), (90, math.pi, 'clamp_sideways'), (90, -0.15, 'clamp_sideways'),
    (90, 2 * math.pi - 0.1, 'clamp_sideways'), (90, 0.3, 'clamp_sideways'), (90, math.pi - 0.85, 'clamp_sideways'),
    (90, 0.9, 'clamp'), (90, math.pi / 2, 'clamp'), (90, None, 'clamp'),
    (110, math.pi - 0.2, 'clamp_sideways'), (110, 1.0, 'clamp_sideways'), (110, 1.1, 'clamp'),
    (110, math.pi / 2, 'clamp')])
def test_the_full_clamp_row_follows_the_roll(mm, roll, row):
    assert cs.full_row(BOOK.for_diameter(mm), roll) == row


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
