"""Junctions taken rear first in the physics twin, in process (SimHarness).

The robot starts where a junction taken front first leaves it, in the pipe
past the junction, facing away from it, clamped as that PAB ends (Clamp
Sideways toward a turn, Clamp Straight past a T-joint open upward), and
the same goal with a negative search distance takes the junction back
with the rear part leading (the robot drives backwards):

- MITRE_BEND LEFT / RIGHT, 90 and 110 mm: the rear steers into the old pipe,
  the front is pulled through, and every module ends in the old pipe,
  clamped on the same side (ground truth, read by the test only);
- T_JOINT STRAIGHT past a T-joint open upward, 90 and 110 mm: the rear V
  senses the hole, each part crosses it open, and the whole robot ends
  before the T-joint, clamped upright.

The twin lays the robot along the world's x axis, so each world here is
built with the pipe past the junction heading along x: a mitre bend
turning the other way first (turning right, then left, to come back
left). Short goals, one each; run a few at a time.
"""
import math

import pytest
import yaml

from pirate.sequencer.pabs import codes
from pirate.testing.harness import SimHarness
from pirate.world import network
from test_pab_junction_twin import APEX_WHEELS, JOINT_BODIES, SIDES, clamped_sideways
from test_sequencer_sim import assert_ended, run_bounded
from test_sim_twin_sequencer import robot_wait

#: The primitives of a rear-first turn, up to the drive into the old pipe (then Clamp Sideways straightens).
TURN_BACK = ['unclamp rear partial', 'steer rear', 'clamp rear at the corner', 'swing the middle',
             'move front trail', 'bring the front through', 'clamp front', 'clamp rear', 'drive into the new pipe',
             'stop wheels']
CROSSING_BACK = ['look for the junction', 'stop wheels', 'unclamp rear partial', 'drive rear across', 'stop wheels',
                 'clamp rear', 'unclamp front partial', 'drive front across', 'stop wheels', 'clamp front']
#: The robot's middle past the junction's exit at the start: where a turn taken front first leaves it
#: (config/supervisory.yaml turn_end_mm), clear of the corner.
START_PAST_MM = {90: 400, 110: 500}
OTHER = {'left': 'right', 'right': 'left'}


def back_world(tmp_path, junction, mm, turn_first=None):
    """A world whose last straight, where the robot starts, heads along x past
    ``junction`` (a piece spec), reached through ``turn_first`` (a mitre bend's
    turn) first when the junction turns; (world path, network)."""
    pieces = [{'type': 'straight', 'length_mm': 200}, {'type': 'mitre', 'turn': turn_first}] if turn_first else []
    pieces += [{'type': 'straight', 'length_mm': 800}, junction, {'type': 'straight', 'length_mm': 900},
               {'type': 'cap'}]
    data = {'name': 'back_%s_%d' % ('_'.join(str(v) for v in junction.values()), mm), 'diameter_mm': mm,
            'pieces': pieces}
    exit_mm = 1000.0 * sum(piece.length for piece in network.build(dict(data, start={'at_mm': 100})).pieces[:-2])
    data['start'] = {'at_mm': exit_mm + START_PAST_MM[mm]}
    path = tmp_path / ('%s.yaml' % data['name'])
    path.write_text(yaml.safe_dump(data))
    return str(path), network.load(str(path))


def in_pipe(piece, point):
    """True when ``point`` (m, world) lies inside straight ``piece``."""
    origin, axes = piece.entry
    offset = [p - o for p, o in zip(point, origin)]
    along = sum(a * b for a, b in zip(offset, axes[0]))
    across = math.sqrt(max(sum(v * v for v in offset) - along * along, 0.0))
    return 0.0 <= along <= piece.length and across < piece.diameter / 2


@pytest.mark.parametrize('mm', [90, 110])
@pytest.mark.parametrize('side', sorted(SIDES))
def test_a_mitre_bend_taken_rear_first_ends_in_the_old_pipe(tmp_path, side, mm):
    option, roll, _ = SIDES[side]
    path, world = back_world(tmp_path, {'type': 'mitre', 'turn': side}, mm, OTHER[side])
    old_pipe = world.pieces[-4]
    with SimHarness(world=path, orientation=roll) as h:
        clamped_sideways(h, option, mm)
        reason, outcome = run_bounded(h, h.goal(codes.MITRE_BEND, mm, option=option, distance=-800.0), 200.0)
        assert_ended(reason, outcome)
        executed = [name for name in h.prims.executed if name != 'level the rear']
        assert executed[:len(TURN_BACK)] == TURN_BACK
        assert ('level the rear' in h.prims.executed) is (mm == 110)    # config/guards_<mm>.yaml turn level_front
        assert 'rear first' in outcome.message and outcome.junction_odometry < 0.0
        ended_roll = h.ground_truth()['roll']      # the clamp's band holds where the PAB ends (it settles after)
        robot_wait(h, 2.0)
        truth = h.ground_truth()
        outside = [body for body in JOINT_BODIES if not in_pipe(old_pipe, truth['poses'][body][0])]
        assert not outside, (outside, truth['poses'])           # every module in the old pipe
        assert abs(math.remainder(ended_roll - roll, 2 * math.pi)) <= 0.05, ended_roll
        assert h.server.status() == 'Idle Clamped'


@pytest.mark.parametrize('mm', [90, 110])
def test_a_t_joint_open_upward_gone_straight_through_rear_first_ends_before_it(tmp_path, mm):
    path, world = back_world(tmp_path, {'type': 'tee', 'enter': 'run', 'side': 'up'}, mm)
    before = world.pieces[0]
    with SimHarness(world=path) as h:
        reason, outcome = run_bounded(h, h.goal(codes.CLAMP_STRAIGHT, mm))
        assert_ended(reason, outcome)
        reason, outcome = run_bounded(h, h.goal(codes.T_JOINT, mm, option=codes.STRAIGHT, distance=-800.0))
        assert_ended(reason, outcome)
        assert h.prims.executed[:len(CROSSING_BACK)] == CROSSING_BACK
        assert -600.0 < outcome.junction_odometry < -200.0 and not outcome.junction_missing
        robot_wait(h, 2.0)
        truth = h.ground_truth()
        outside = [body for body in JOINT_BODIES if not in_pipe(before, truth['poses'][body][0])]
        assert not outside, (outside, truth['poses'])           # the whole robot back before the T-joint
        assert APEX_WHEELS <= set(truth['wheel_contacts'])
        assert h.server.status() == 'Idle Clamped'
