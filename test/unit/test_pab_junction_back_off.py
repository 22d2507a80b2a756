"""A turn's steering levels the front part and backs off an edge its front stands at.

A turn's start rotates the open front part onto the side's roll (110 mm,
the row's ``level_front``; a resumed steering does not). The steering then
drives the front toward the opening until Bend II says it is round the
corner. Wheels standing ``back_off_after_s`` (the turn row) say
the front met an edge it does not get past; it backs off ``back_off_mm``
of odometry and steers on, within the steering's own time bound. Here a
small kinematic stand-in replaces the twin: the wheels move the odometry
at the set speed except where an edge stops them, and the front turns
round once it reaches the edge after backing off (as the twin's 110 mm
T-joint entered through its run did: measurements.md#turn-back-off). The
twin itself is swept by bench/pab_junction_sweep.
"""
import collections
import math

import pytest

from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS, codes
from pirate.sequencer.pabs import junction as jn
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.server import PabContext
from pirate.state.feed import RobotView, TimedOut

BOOK = GuardBook(*load_files())
Goal = collections.namedtuple('Goal', 'name option distance speed pipe_diameter')
STEP_S = 0.05
FLAT = dict(front_tilt=0.5, bend_i=-0.9, bend_ii=0.45, bend_iii=0.45, bend_iv=-0.9)


class EdgeWorld(object):
    """Primitives over a stand-in robot: odometry follows the wheels (mm/s) at
    ``STEP_S`` robot s a state, except forward at ``edge_mm`` (the wheels
    stand), and backward where ``back_stops_mm`` is set (stands there too).
    After ``turns_after`` back-offs the front turns round on reaching the edge."""

    def __init__(self, edge_mm=math.inf, turns_after=math.inf, back_stops_mm=-math.inf, roll=math.pi):
        self.edge_mm, self.turns_after, self.back_stops_mm, self.roll = edge_mm, turns_after, back_stops_mm, roll
        self.wheels, self.odometry, self.stamp, self.backed = 0.0, 0.0, 0.0, 0
        self.ran, self.wheel_log, self.backed_to_mm, self.rotated = [], [], math.inf, []
        self.view = self._view(0.0)

    def _view(self, velocity):
        round_ = self.backed >= self.turns_after and self.odometry >= self.edge_mm
        angles = dict(FLAT, bend_ii=2.0 if round_ else FLAT['bend_ii'])
        return RobotView(angles, self.roll, self.odometry, velocity, self.stamp, {})

    def _step(self):
        moved = self.wheels * STEP_S
        if moved > 0:
            moved = max(0.0, min(moved, self.edge_mm - self.odometry))
        elif moved < 0:
            moved = min(0.0, max(moved, self.back_stops_mm - self.odometry))
        self.odometry += moved
        if self.wheels < 0:
            self.backed_to_mm = min(self.backed_to_mm, self.odometry)
        self.stamp += STEP_S
        self.view = self._view(moved / STEP_S)

    # --- the primitives and feed a PabContext needs ---------------------------
    def latest(self):
        return self.view

    def change_control_mode(self, joint, mode):
        """Modes do not matter here."""

    def move_module(self, joint, counts):
        """Only the wheels move this stand-in."""

    def drive_at_velocity(self, mm_s):
        if mm_s < 0 < self.wheels:
            self.backed += 1
        self.wheels = mm_s
        self.wheel_log.append(mm_s)

    def rotate(self, target_rad, name='rotate'):
        self.ran.append((name, self.stamp))
        self.rotated.append((target_rad, list(self.wheel_log)))

    def unclamp(self, part, partial=False):
        self.ran.append(('unclamp %s%s' % (part, ' partial' if partial else ''), self.stamp))

    def follow(self, name, act, done, text, timeout):
        self.ran.append((name, self.stamp))
        end = self.stamp + timeout
        while not done(self.view):
            act(self.view)
            self._step()
            if self.stamp >= end:
                raise TimedOut('%s: %s not reached within %.1f s' % (name, text, timeout))
        return self.view


def steer(world, mm=110, speed=0.0, distance=800.0, option=codes.LEFT, steps=(jn.STEERING_FRONT,)):
    """Run a mitre's ``steps`` (LEFT unless ``option`` says; by default the
    steering alone, as a resumed turn enters it) in ``world``: the PAB."""
    guards = BOOK.for_diameter(mm)
    goal = Goal(codes.MITRE_BEND, option, distance, speed, mm)
    pab = PABS[codes.MITRE_BEND][1].for_goal(goal)
    for step in steps:
        pab.actions()[step](PabContext(world, world, guards, goal, lambda *state: None))
    return pab


FROM_THE_START = (jn.UNCLAMPING_FRONT, jn.STEERING_FRONT)


def row(mm=110):
    return BOOK.for_diameter(mm).row('turn')


@pytest.mark.parametrize('mm', [90, 110])
def test_both_turn_rows_say_when_and_how_far_to_back_off(mm):
    turn = row(mm)
    assert 0.0 < float(turn['back_off_after_s']) < float(turn['steer_base_s'])
    assert 0.0 < float(turn['back_off_mm']) < mm
    assert float(turn['steer_beyond_mm']) > 0.0


def test_a_front_that_stands_at_an_edge_backs_off_and_steers_on_into_the_opening():
    world = EdgeWorld(edge_mm=300.0, turns_after=1)
    pab = steer(world)
    stand_s = float(row()['back_off_after_s'])
    assert [name for name, _ in world.ran] == ['steer front', 'back off the edge', 'steer front']
    assert world.wheel_log == [25.0, -25.0, 0.0, 25.0, 0.0]       # steer, back, stop, steer, stop
    reached_edge_s = 300.0 / 25.0
    backed_at = world.ran[1][1]
    assert backed_at == pytest.approx(reached_edge_s + stand_s, abs=2 * STEP_S)   # stood back_off_after_s first
    assert pab.backed_off == 1 and pab.steered is not None
    assert pab.junction_odometry == pytest.approx(300.0)


def test_the_back_off_drives_back_its_distance_of_odometry():
    world = EdgeWorld(edge_mm=300.0, turns_after=1)
    steer(world)
    assert world.backed_to_mm == pytest.approx(300.0 - float(row()['back_off_mm']), abs=25.0 * STEP_S)


def test_wheels_that_never_stand_never_back_off():
    world = EdgeWorld(edge_mm=300.0, turns_after=0)     # the front turns round at the edge at once
    pab = steer(world)
    assert [name for name, _ in world.ran] == ['steer front']
    assert pab.backed_off == 0 and -25.0 not in world.wheel_log


def test_an_edge_the_front_never_gets_past_ends_at_the_steerings_own_bound_with_junction_missing():
    world = EdgeWorld(edge_mm=300.0)                    # never turns round
    turn = row()
    limit_s = float(turn['steer_base_s']) + float(turn['steer_s_per_mm']) * 800.0
    with pytest.raises(jn.JunctionMissing) as missing:
        steer(world)
    assert world.stamp == pytest.approx(limit_s, abs=2 * STEP_S)       # not a second more for the back-offs
    backs = sum(1 for name, _ in world.ran if name == 'back off the edge')
    assert backs >= 2
    assert 'backed off an edge %d times' % backs in str(missing.value)
    assert world.wheel_log[-1] == 0.0                                  # the wheels stopped


def test_with_no_opening_the_steering_stops_at_the_goals_distance_and_never_clamps_at_a_corner():
    """The goal's distance bounds the whole steering (a mission's map bound):
    not a step of odometry past it, JunctionMissing, and nothing of the turn
    proper ran (the table leaves the steering for the corner only when the
    front is round)."""
    world = EdgeWorld()                                  # a straight pipe: nothing to stand at, nothing to turn into
    with pytest.raises(jn.JunctionMissing) as missing:
        steer(world, distance=100.0, steps=FROM_THE_START)
    assert 100.0 <= world.odometry <= 100.0 + 25.0 * STEP_S           # long before the time bound would end it
    assert 'no opening toward the left within 100 mm' in str(missing.value)
    assert world.wheel_log[-1] == 0.0
    assert [name for name, _ in world.ran] == ['unclamp front partial', 'level the front', 'steer front']


def test_a_goal_of_distance_zero_steers_the_search_and_the_beyond_distance():
    world = EdgeWorld()
    with pytest.raises(jn.JunctionMissing):
        steer(world, distance=0.0)
    last_mm = float(BOOK.for_diameter(110).row('junction')['search_mm']) + float(row()['steer_beyond_mm'])
    assert last_mm < world.odometry <= last_mm + 25.0 * STEP_S


def test_a_rear_first_turn_steers_no_further_than_its_distance_either():
    world = EdgeWorld()
    with pytest.raises(jn.JunctionMissing):
        steer(world, distance=-300.0, steps=(jn.table.state(jn.table.STEERING_LEAD, 'rear'),))
    assert -300.0 - 25.0 * STEP_S <= world.odometry <= -300.0


def test_a_back_off_that_cannot_move_ends_at_its_own_bound_and_the_steering_goes_on():
    world = EdgeWorld(edge_mm=300.0, back_stops_mm=300.0)    # stuck both ways
    with pytest.raises(jn.JunctionMissing):
        steer(world)
    names = [name for name, _ in world.ran]
    assert names[:4] == ['steer front', 'back off the edge', 'steer front', 'back off the edge']


@pytest.mark.parametrize('option, roll, rotation', [
    (codes.LEFT, 3.05, 3.05 - math.pi),          # the twin's rear after Clamp Sideways LEFT from 60 deg
    (codes.LEFT, -3.10, math.pi - 3.10),         # the same side, the roll read past pi
    (codes.RIGHT, 0.05, 0.05),
    (codes.RIGHT, -0.04, -0.04),
])
def test_the_front_part_is_levelled_on_the_turns_side_before_the_wheels_turn(option, roll, rotation):
    world = EdgeWorld(edge_mm=300.0, turns_after=0, roll=roll)
    steer(world, option=option, steps=FROM_THE_START)
    (target, wheels_before), = world.rotated
    assert target == pytest.approx(rotation)          # front roll = rear roll - rotation = the side's
    assert wheels_before == []
    assert [name for name, _ in world.ran] == ['unclamp front partial', 'level the front', 'steer front']


def test_in_90_mm_the_front_part_is_not_levelled():
    world = EdgeWorld(edge_mm=300.0, turns_after=0, roll=3.05)
    steer(world, mm=90, steps=FROM_THE_START)
    assert world.rotated == []
    assert [name for name, _ in world.ran] == ['unclamp front partial', 'steer front']


def test_a_turn_resumed_into_its_steering_does_not_level_the_front_part_again():
    world = EdgeWorld(edge_mm=300.0, turns_after=0, roll=3.05)
    steer(world)                                      # entered at STEERING_FRONT, as RESUME_STEERING does
    assert world.rotated == []


def test_standing_counts_only_wheels_still_on_end():
    standing = motions.Standing(8.0)
    views = [(0.0, 0.0), (5.0, 0.0), (6.0, 20.0), (7.0, 0.0), (14.9, 0.5), (15.0, 0.0)]
    said = [standing.long(RobotView(FLAT, math.pi, 0.0, velocity, stamp, {})) for stamp, velocity in views]
    assert said == [False, False, False, False, False, True]
