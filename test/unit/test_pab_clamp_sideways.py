"""Clamp Sideways: the Clamp Straight machine at another target.

On the kinematic robot (report Table 4.5 only, no physics): from start
rolls every 15 degrees of the working range 0..pi, Clamp Sideways LEFT (pi)
and RIGHT (0) and Clamp Straight (pi/2) end with both parts clamped, the
rear in the straight region around the target and the rotation aligned;
the regions are Table 5.4's moved to the target.
"""
import math

import pytest

from pirate.sequencer.pabs import codes
from pirate.sequencer.pabs.clamp import UPRIGHT, Clamp, region_around, target_of

from kinematic_robot import BOOK, KinematicRobot, run

GUARDS = BOOK.for_diameter(90)
TARGETS = {'RIGHT': (codes.RIGHT, 0.0), 'STRAIGHT': (codes.NONE, UPRIGHT), 'LEFT': (codes.LEFT, math.pi)}
ROLLS = [math.radians(d) for d in range(0, 181, 15)]


class Goal(object):
    def __init__(self, name, option):
        self.name, self.option = name, option


def goal_for(side):
    option, _ = TARGETS[side]
    return Goal(codes.CLAMP_STRAIGHT if side == 'STRAIGHT' else codes.CLAMP_SIDEWAYS, option)


@pytest.mark.parametrize('side', sorted(TARGETS))
def test_target_of_each_goal(side):
    assert target_of(goal_for(side)) == TARGETS[side][1]
    assert Clamp.for_goal(goal_for(side)).name == ('Clamp Straight' if side == 'STRAIGHT' else 'Clamp Sideways')


def test_a_sideways_goal_without_a_side_has_no_target():
    assert target_of(Goal(codes.CLAMP_SIDEWAYS, codes.NONE)) is None
    assert 'side' in Clamp.for_goal(Goal(codes.CLAMP_SIDEWAYS, codes.STRAIGHT)).check(
        Goal(codes.CLAMP_SIDEWAYS, codes.STRAIGHT), None, GUARDS)


@pytest.mark.parametrize('target', [0.0, UPRIGHT, math.pi])
def test_regions_are_measured_around_the_target(target):
    for name in ('straight', 'nominal'):
        low, high = GUARDS.region(name)
        moved = region_around(GUARDS, name, target)
        assert moved[1] - moved[0] == pytest.approx(high - low)
        assert (moved[0] + moved[1]) / 2 - target == pytest.approx((low + high) / 2 - UPRIGHT)


@pytest.mark.parametrize('side', sorted(TARGETS))
@pytest.mark.parametrize('roll', ROLLS, ids=['%d deg' % round(math.degrees(r)) for r in ROLLS])
def test_clamp_at_the_target_from_any_roll(side, roll):
    target = TARGETS[side][1]
    robot = KinematicRobot(roll, 0.0, front_tilt=0.0)
    pab = Clamp.for_goal(goal_for(side))
    message = run(pab, robot, goal_for(side))
    straight = region_around(GUARDS, 'straight', target)
    assert straight[0] <= robot.rear <= straight[1], (robot.rear, robot.executed)
    assert abs(robot.rotation) <= GUARDS.align_tolerance
    assert robot.clamped == {'front': True, 'rear': True}
    assert 'target %.3f' % target in message
    nominal = region_around(GUARDS, 'nominal', target)
    custom = [step for step in robot.executed if 'custom' in step]
    assert bool(custom) == (not nominal[0] <= roll <= nominal[1])   # custom clamps only non-nominal


@pytest.mark.parametrize('side, roll', [('RIGHT', math.pi), ('LEFT', 0.0)])
def test_a_front_left_at_the_sideways_lift_is_lifted_again_before_its_later_custom_clamps(side, roll):
    """Non-nominal start with the front at the sideways lift (0.16 rad, below
    Table 5.3's later lift 0.3): the front custom clamps after the first
    need the front lifted to move_front_later (twin: at 0.17 rad the front V
    met the wall at -0.680, short of -0.72)."""
    later = GUARDS.move('move_front_later').guard
    robot = KinematicRobot(roll, 0.0, front_tilt=GUARDS.move('move_front_sideways').guard)
    tilts = []
    clamp = robot.clamp
    robot.clamp = lambda part, kind='clamp': (tilts.append((kind, robot.angles['front_tilt'])), clamp(part, kind))
    run(Clamp.for_goal(goal_for(side)), robot, goal_for(side))
    later_custom = [tilt for kind, tilt in tilts if kind.startswith('clamp_front_custom') and '_first' not in kind]
    assert later_custom and min(later_custom) >= later, tilts


@pytest.mark.parametrize('mm, side, row', [
    (110, 'RIGHT', 'unclamp_partial_sideways'), (110, 'LEFT', 'unclamp_partial_sideways'),
    (110, 'STRAIGHT', 'unclamp_partial'), (90, 'RIGHT', 'unclamp_partial'), (90, 'LEFT', 'unclamp_partial')])
def test_a_part_turned_onto_a_side_is_opened_past_the_chord_first(mm, side, row):
    """110 mm: the report's partial unclamp (-0.9 rad) does not open the V
    past the chord it meets lying on a side (-0.893), so Clamp Sideways
    opens it further (config/guards_110.yaml unclamp_partial_sideways;
    twin: the front jammed 0.29 rad short of the side otherwise). Clamp
    Straight, and 90 mm (its partial is 0.12 rad past the chord), keep the
    plain row."""
    robot = KinematicRobot(math.radians(150 if side == 'RIGHT' else 30), 0.0, front_tilt=0.0, pipe_diameter=mm)
    run(Clamp.for_goal(goal_for(side)), robot, goal_for(side))
    assert robot.unclamp_rows and set(robot.unclamp_rows) == {row}, robot.unclamp_rows
    chord_outer = robot.guards.pair('clamp_sideways', 'front').outer.guard if mm == 110 else None
    if row.endswith('_sideways'):
        assert robot.guards.pair(row, 'front').outer.guard > chord_outer + 0.05     # more open than the wall on a side
