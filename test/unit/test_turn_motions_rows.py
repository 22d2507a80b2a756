"""A turn clamps each part with the full guards of that part's own roll.

The rear's roll is the IMU's; the front's is the rear's less the rotation
(Table 4.5). Near the edge of the sideways band (``clamp_sideways``
``within_rad``, config/guards_<mm>.yaml) the rotation can put one part on a
side and the other not. The clamp state the server reads afterwards
(:func:`pirate.sequencer.clamp_state.classify_part`) judges each part by its
own roll, so the turn's clamps must pick their guards the same way, or a
part clamps to guards its class then does not call clamped.
"""
import collections
import math

import pytest

from pirate.sequencer import clamp_state
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import turn_motions as motions
from pirate.sequencer.server import PabContext
from pirate.state.feed import RobotView

BOOK = GuardBook(*load_files())
FLAT = dict(front_tilt=0.5, bend_i=-0.9, bend_ii=0.45, bend_iii=0.45, bend_iv=-0.9)
Clamp = collections.namedtuple('Clamp', 'part row')


class Still(object):
    """A robot that stays at one reading and records the clamps asked of it."""

    def __init__(self, orientation, rotation):
        self.view = RobotView(dict(FLAT, rotation=rotation), orientation, 0.0, 0.0, 0.0, {})
        self.clamps = []

    def latest(self):
        return self.view

    def clamp(self, part, row):
        self.clamps.append(Clamp(part, row))


def context(mm, orientation, rotation):
    robot = Still(orientation, rotation)
    return PabContext(robot, robot, BOOK.for_diameter(mm), None, lambda *state: None), robot


def band_rad(mm):
    return float(BOOK.for_diameter(mm).row('clamp_sideways')['within_rad'])


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('side', [0.0, math.pi])
def test_a_front_rotated_off_the_band_clamps_upright_while_the_rear_clamps_sideways(mm, side):
    rear_roll = side + (band_rad(mm) - 0.1)        # inside the band
    rotation = -0.2                                 # front roll = rear roll - rotation: 0.1 rad outside
    ctx, robot = context(mm, rear_roll, rotation)
    motions.clamp_full(ctx, 'front')
    motions.clamp_full(ctx, 'rear')
    assert robot.clamps == [Clamp('front', 'clamp'), Clamp('rear', 'clamp_sideways')]


@pytest.mark.parametrize('mm', [90, 110])
def test_a_front_rotated_onto_the_side_clamps_sideways_while_the_rear_clamps_upright(mm):
    rear_roll = math.pi - (band_rad(mm) + 0.1)     # outside the band
    rotation = -0.2                                 # the front 0.1 rad inside it
    ctx, robot = context(mm, rear_roll, rotation)
    motions.clamp_full(ctx, 'front')
    motions.clamp_full(ctx, 'rear')
    assert robot.clamps == [Clamp('front', 'clamp_sideways'), Clamp('rear', 'clamp')]


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('rear_roll, rotation', [(2.5, 0.3), (2.5, -0.6), (1.571, 0.0), (0.9, 0.7), (-0.3, -0.5)])
def test_the_turns_row_is_the_one_the_clamp_state_judges_the_part_by(mm, rear_roll, rotation):
    ctx, robot = context(mm, rear_roll, rotation)
    angles = dict(FLAT, rotation=rotation)
    for part in clamp_state.PARTS:
        roll = clamp_state.part_roll(part, angles, rear_roll)
        assert motions.full_row_of(ctx.guards, robot.view, part) == clamp_state.full_row(ctx.guards, roll)
