"""Pirate Server without ROS: which goals it refuses, and why; one exit path.

Every refusal must come at once (reserve) with a message that names the
reason; an accepted goal ends in exactly one outcome and, unless it
succeeded, with the safe hold on the wire.
"""
import collections
import math

import pytest

from pirate.state.feed import RobotFeed, RobotView
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS
from pirate.sequencer.pabs.base import Ended, Pab, PabFailed
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.pabs import codes
from pirate.sequencer.server import ABORTED, IDLE_UNCLAMPED, PREEMPTED, SUCCEEDED, PirateServer

from fakes import command_arrays

CLAMP_STRAIGHT, CLAMP_SIDEWAYS, DRIVE, HOME = 0, 1, 4, 5
CLAMPED = dict(bend_i=-0.8, bend_ii=0.4, bend_iii=0.4, bend_iv=-0.8)
ON_WALL = dict(bend_i=241.0, bend_iv=241.0)     # outer springs at the clamp's torque, mNm


class Goal(object):
    """The fields of Pirate.action's goal."""

    def __init__(self, name, pipe_diameter=90, distance=0.0, speed=0.0, option=0):
        self.name, self.pipe_diameter, self.distance = name, pipe_diameter, distance
        self.speed, self.option = speed, option


class Clock(object):
    now = 50.0

    def __call__(self):
        return self.now


def state(orientation=math.pi / 2, efforts=None, **angles):
    base = {n: 0.0 for n in ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')}
    base.update(angles)
    return RobotView(base, orientation, 0.0, 0.0, 1.0, efforts or {})


@pytest.fixture
def rig():
    wires, setpoint, control, limit = command_arrays()
    clock = Clock()
    feed = RobotFeed(0.3, clock=clock)
    prims = MotionPrimitives(setpoint, control, limit, feed)
    started, logs = [], []
    server = PirateServer(prims, feed, GuardBook(*load_files()), lambda: started.append(True),
                          log=logs.append)
    return server, feed, clock, wires, logs


def refused(server, goal, *words):
    active = server.active
    reason = server.reserve(goal)
    assert reason, 'goal was accepted'
    for word in words:
        assert word.lower() in reason.lower(), (word, reason)
    assert server.active == active          # a refusal changes nothing
    return reason


def test_straight_clamp_is_accepted(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    assert server.reserve(Goal(CLAMP_STRAIGHT)) is None
    assert server.active == 'CLAMP_STRAIGHT'


def test_unknown_pab_code(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    reason = refused(server, Goal(9), 'unknown PAB', '9')
    for code, (name, _) in PABS.items():
        assert name in reason           # the message lists what is known


def test_clamp_sideways_without_a_side(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    refused(server, Goal(CLAMP_SIDEWAYS, option=0), 'CLAMP_SIDEWAYS', 'side', 'LEFT', 'RIGHT')


@pytest.mark.parametrize('name,option,words', [
    (CLAMP_STRAIGHT, 5, ('CLAMP_STRAIGHT takes option 0 NONE', 'not 5 DOWN')),
    (CLAMP_SIDEWAYS, 3, ('CLAMP_SIDEWAYS takes option 1 LEFT or 2 RIGHT', 'not 3 STRAIGHT')),
    (CLAMP_SIDEWAYS, 7, ('1 LEFT or 2 RIGHT', '7 (no option of Pirate.action)')),
    (DRIVE, 1, ('DRIVE takes option 0 NONE', 'not 1 LEFT')),
    (HOME, 4, ('HOME takes option 0 NONE', 'not 4 UP')),
])
def test_an_option_the_pab_does_not_take_is_refused_with_those_it_takes(rig, name, option, words):
    server, feed, _, _, _ = rig
    feed.push(state())
    refused(server, Goal(name, option=option), *words)


def test_clamp_sideways_non_nominal_in_110_mm_is_accepted(rig):
    # Upright is 90 degrees from either side: non-nominal; the 110 mm guards
    # have derived custom clamps (the twin clamps from there).
    server, feed, _, _, _ = rig
    feed.push(state())
    assert server.reserve(Goal(CLAMP_SIDEWAYS, pipe_diameter=110, option=1)) is None


def test_pipe_without_guards(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    refused(server, Goal(CLAMP_STRAIGHT, pipe_diameter=100), '100 mm', '90', '110')


def test_drive_while_unclamped(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    refused(server, Goal(DRIVE, distance=50.0), 'DRIVE', 'clamped')


def test_drive_refused_with_clamp_angles_short_of_the_wall(rig):
    # A cancel between the clamp guard and the wall leaves the
    # angles past the guards with the outer springs slack; that is no clamp.
    server, feed, _, _, _ = rig
    feed.push(state(efforts=dict(bend_iii=-194.0, bend_iv=-34.0), **CLAMPED))
    refused(server, Goal(DRIVE, distance=50.0), 'DRIVE', 'clamped')


def test_drive_in_the_wrong_diameter_says_what_it_senses_with_which_guards(rig):
    """Clamped in 90 mm, a 110 mm Drive reads the V's angles against the
    110 mm guards: the refusal names them and what each part is by them."""
    server, feed, _, _, _ = rig
    feed.push(state(efforts=ON_WALL, **CLAMPED))
    refused(server, Goal(DRIVE, pipe_diameter=110, distance=50.0), 'by the 110 mm guards it senses the front part',
            'the rear')


def test_drive_speed_above_maximum(rig):
    server, feed, _, _, _ = rig
    feed.push(state(efforts=ON_WALL, **CLAMPED))
    refused(server, Goal(DRIVE, distance=50.0, speed=200.0), 'speed', '200', '170')
    refused(server, Goal(DRIVE, distance=50.0, speed=-20.0), 'speed')


@pytest.mark.parametrize('distance', [0.0, math.nan, math.inf, 1e6, -1e6])
def test_drive_distance_out_of_range(rig, distance):
    server, feed, _, _, _ = rig
    feed.push(state(efforts=ON_WALL, **CLAMPED))
    refused(server, Goal(DRIVE, distance=distance, speed=150.0), 'distance')


def test_drive_clamped_and_in_range_is_accepted(rig):
    server, feed, _, _, _ = rig
    feed.push(state(efforts=ON_WALL, **CLAMPED))
    assert server.reserve(Goal(DRIVE, distance=-30.0, speed=150.0)) is None


def test_no_robot_state(rig):
    server, _, _, _, _ = rig
    refused(server, Goal(CLAMP_STRAIGHT), 'no robot state')


def test_stale_robot_state(rig):
    server, feed, clock, _, _ = rig
    feed.push(state())
    clock.now += 1.0
    refused(server, Goal(HOME), 'no robot state')


def test_goal_while_one_runs_is_refused_not_queued(rig):
    server, feed, _, _, _ = rig
    feed.push(state())
    assert server.reserve(Goal(CLAMP_STRAIGHT)) is None
    refused(server, Goal(HOME), 'running', 'CLAMP_STRAIGHT', 'not queued')
    assert server.active == 'CLAMP_STRAIGHT'


@pytest.mark.parametrize('orientation', [0.0, math.pi, 1.2])
def test_non_nominal_start_in_110_is_accepted(rig, orientation):
    server, feed, _, _, _ = rig
    feed.push(state(orientation=orientation))
    assert server.reserve(Goal(CLAMP_STRAIGHT, pipe_diameter=110)) is None


def test_nominal_start_in_110_is_accepted(rig):
    server, feed, _, _, _ = rig
    feed.push(state(orientation=1.45))
    assert server.reserve(Goal(CLAMP_STRAIGHT, pipe_diameter=110)) is None


# --- run: one exit path ----------------------------------------------------

def assert_safe(sent):
    for index in (1, 2, 3, 6, 7, 11):      # front, bends I-IV, wheels
        assert sent[index] == 0, (index, sent)


def test_cancel_before_the_first_action_preempts_safely(rig):
    server, feed, _, wires, logs = rig
    feed.push(state())
    goal = Goal(CLAMP_STRAIGHT)
    assert server.reserve(goal) is None
    server.cancel()
    assert server.cancelled
    outcome = server.run(goal)
    assert outcome.status == PREEMPTED and 'cancelled' in outcome.message
    assert_safe(wires['setpoint'].sent[-1])
    assert server.active is None and server.status() == IDLE_UNCLAMPED and not server.cancelled
    assert logs[-1] == outcome.message
    assert server.reserve(goal) is None      # ready for the next goal, cancel cleared
    assert not server.cancelled


def test_a_goal_cancelled_for_a_rogue_writer_says_who_wrote(rig):
    """The mission's reason after a rogue writer was "step N was cancelled
    outside the mission": the goal's result did not name the writer."""
    server, feed, _, _, _ = rig
    feed.push(state())
    rogue = 'second writer on /pirate/setpoint_array: /rostopic_4711 (only /pirate_manager may command the robot)'
    assert server.reserve(Goal(CLAMP_STRAIGHT)) is None
    server.cancel(rogue)
    outcome = server.run(Goal(CLAMP_STRAIGHT))
    assert outcome.status == PREEMPTED and outcome.message.endswith(': ' + rogue), outcome.message
    assert server.reserve(Goal(CLAMP_STRAIGHT)) is None
    server.cancel()                                     # the operator's cancel of the next goal
    assert 'rostopic' not in server.run(Goal(CLAMP_STRAIGHT)).message


def test_lost_feedback_aborts_safely(rig):
    server, feed, clock, wires, _ = rig
    feed.push(state())
    goal = Goal(CLAMP_STRAIGHT)
    assert server.reserve(goal) is None
    clock.now += 1.0
    outcome = server.run(goal)
    assert outcome.status == ABORTED and 'no robot state' in outcome.message
    assert_safe(wires['setpoint'].sent[-1])
    assert server.active is None


class Broken(Pab):
    name = 'Broken'

    def check(self, goal, view, guards):
        return None

    def run(self, ctx):
        raise ZeroDivisionError('a bug')


class Instant(Pab):
    name = 'Instant'

    def run(self, ctx):
        return 'nothing to do'


def test_a_bug_in_a_pab_aborts_safely_and_is_logged(rig, monkeypatch):
    server, feed, _, wires, logs = rig
    monkeypatch.setitem(PABS, 7, ('BROKEN', Broken))
    feed.push(state())
    goal = Goal(7)
    assert server.reserve(goal) is None
    outcome = server.run(goal)
    assert outcome.status == ABORTED and 'internal error' in outcome.message
    assert any('ZeroDivisionError' in line for line in logs)
    assert_safe(wires['setpoint'].sent[-1])
    assert server.active is None


def test_success_leaves_the_robot_alone_and_sets_the_state(rig, monkeypatch):
    server, feed, _, wires, _ = rig
    monkeypatch.setitem(PABS, 7, ('INSTANT', Instant))
    feed.push(state())
    goal = Goal(7)
    assert server.reserve(goal) is None
    before = len(wires['setpoint'].sent)
    outcome = server.run(goal)
    assert outcome.status == SUCCEEDED and 'nothing to do' in outcome.message
    assert len(wires['setpoint'].sent) == before     # no safe hold after success
    # The state is what the robot senses, not what the PAB claims to leave.
    assert server.status() == IDLE_UNCLAMPED and server.active is None


#: A record as a PAB leaves one: a namedtuple of plain values.
HALF_DONE = collections.namedtuple('HalfDone', 'odometry_mm')(120.0)


class Leaves(Pab):
    """Fails, leaving a record of its run; says what it was handed."""
    name = 'Leaves'
    handed = []

    def carry_on(self, record):
        Leaves.handed.append(record)

    def unfinished(self):
        return HALF_DONE

    def run(self, ctx):
        raise PabFailed('stopped half way')


def test_what_a_goal_left_unfinished_goes_to_the_same_goal_only_and_once_another_runs_is_gone(rig, monkeypatch):
    """A turn cancelled while driving into the new pipe senses like a robot
    before a bend: only the server's record tells a re-sent turn where it is."""
    server, feed, _, _, _ = rig
    monkeypatch.setitem(PABS, 7, ('LEAVES', Leaves))
    monkeypatch.setitem(PABS, 8, ('INSTANT', Instant))
    monkeypatch.setattr(Leaves, 'handed', [])
    feed.push(state())
    for goal in (Goal(7), Goal(7)):
        assert server.reserve(goal) is None and server.run(goal).status == ABORTED
    assert Leaves.handed == [HALF_DONE] * 2          # the second goal's check and run
    assert server.reserve(Goal(8)) is None and server.run(Goal(8)).status == SUCCEEDED
    assert server.reserve(Goal(7)) is None and server.run(Goal(7)).status == ABORTED
    assert Leaves.handed == [HALF_DONE] * 2          # a goal that succeeded in between dropped it
    assert server.reserve(Goal(7, option=codes.RIGHT)) is None and server.run(Goal(7, option=codes.RIGHT))
    assert Leaves.handed == [HALF_DONE] * 2          # another option is another goal


class Follows(Pab):
    """Ends in its state 'stopped here', or succeeds; says what it was told of the goal before."""
    name = 'Follows'
    told = []

    def follows(self, ended):
        Follows.told.append(ended)

    def run(self, ctx):
        ctx.report('stopped here')
        if ctx.goal.option == codes.RIGHT:
            return 'done'
        raise PabFailed('stopped')


def test_each_pab_is_told_how_the_last_goal_that_ran_ended(rig, monkeypatch):
    """Home reads it: after a turn stopped half round its corner it refuses
    to unclamp there. A refused goal did not run, so it changes nothing."""
    server, feed, _, _, _ = rig
    monkeypatch.setitem(PABS, 7, ('FOLLOWS', Follows))
    monkeypatch.setattr(Follows, 'told', [])
    feed.push(RobotView(dict(state().angles), math.pi / 2, 321.0, 0.0, 1.0, {}))
    assert server.reserve(Goal(7)) is None and server.run(Goal(7)).status == ABORTED
    assert Follows.told == [None, None]                  # its check and its run
    assert server.reserve(Goal(7, option=codes.RIGHT)) is None
    assert Follows.told[-1] == Ended('Follows', 'stopped here', 321.0, ABORTED)
    assert server.run(Goal(7, option=codes.RIGHT)).status == SUCCEEDED
    assert server.reserve(Goal(3, pipe_diameter=55)) is not None        # refused: did not run
    assert server.reserve(Goal(7)) is None
    assert Follows.told[-1].status == SUCCEEDED


def test_pab_codes_match_the_action_definition():
    pirate_msg = pytest.importorskip('pirate.msg')
    goal = pirate_msg.PirateGoal
    for code, (name, _) in PABS.items():
        assert getattr(goal, name) == code
    for option in ('NONE', 'LEFT', 'RIGHT', 'STRAIGHT', 'UP', 'DOWN'):
        assert getattr(goal, option) == getattr(codes, option)
