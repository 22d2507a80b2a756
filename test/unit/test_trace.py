"""The trace of a goal: what ran, with robot times and outcome.

Feedback may be lost; the result carries the trace. Here: the server
records every primitive start and end from the robot's clock, the running
one ends with the goal's outcome, and the progress numbers (time against
timeout, guard against threshold) come from the newest state.
"""
import math

import pytest

from pirate.state.feed import RobotFeed, RobotView
from pirate.sequencer.guards import GuardBook, load_files
from pirate.sequencer.pabs import PABS
from pirate.sequencer.pabs.base import Pab
from pirate.sequencer.primitives import MotionPrimitives
from pirate.sequencer.server import PREEMPTED, SUCCEEDED, PirateServer
from pirate.sequencer.trace import REACHED, Trace, guard_numbers

from fakes import command_arrays

JOINTS = ('front_tilt', 'bend_i', 'bend_ii', 'rotation', 'bend_iii', 'bend_iv')


def view(stamp, **angles):
    base = dict.fromkeys(JOINTS, 0.0)
    base.update(angles)
    return RobotView(base, math.pi / 2, 0.0, 0.0, stamp)


class Goal(object):
    name, pipe_diameter, distance, speed, option = 7, 90, 0.0, 0.0, 0


class TwoSteps(Pab):
    """Lifts the front (the robot state says it is up at once), then waits for a clamp."""
    name = 'TwoSteps'
    check = staticmethod(lambda goal, view, guards: None)
    on_wait = None      # called while the second primitive waits

    def run(self, ctx):
        ctx.prims.wait_for('move front', lambda v: True, 'front_tilt >= 0.400')
        ctx.feed.push(view(3.5, front_tilt=0.41, bend_iv=-0.5))
        if self.on_wait:
            self.on_wait(ctx)
        ctx.prims.wait_for('clamp rear', lambda v: v.angles['bend_iv'] <= -0.77,
                           'bend_iv <= -0.77 and bend_iii >= 0.35', timeout=0.0001)
        return 'done'


@pytest.fixture
def rig(monkeypatch):
    _, setpoint, control, limit = command_arrays()
    feed = RobotFeed(0.3, clock=lambda: 50.0)
    prims = MotionPrimitives(setpoint, control, limit, feed)
    server = PirateServer(prims, feed, GuardBook(*load_files()), lambda: None)
    monkeypatch.setitem(PABS, 7, ('TWO', TwoSteps))
    feed.push(view(2.0))
    assert server.reserve(Goal()) is None
    return server, feed


def test_trace_records_robot_times_and_outcomes_of_a_cancelled_goal(rig, monkeypatch):
    server, feed = rig

    def cancel(ctx):
        assert server.progress() is None       # between two primitives
        feed.cancel()
    monkeypatch.setattr(TwoSteps, 'on_wait', staticmethod(cancel))
    outcome = server.run(Goal())
    assert outcome.status == PREEMPTED
    steps = server.trace.steps
    assert [(s.name, s.start, s.end, s.outcome) for s in steps] == [
        ('move front', 2.0, 2.0, REACHED), ('clamp rear', 3.5, 3.5, PREEMPTED)]
    assert steps[1].guard.startswith('bend_iv <= -0.77')


def test_progress_carries_the_guard_numbers_and_the_time(rig, monkeypatch):
    server, feed = rig
    seen = []

    def look(ctx):
        ctx.prims.notify('clamp rear', 'bend_iv <= -0.77 and bend_iii >= 0.35')
        ctx.feed.push(view(5.0, bend_iv=-0.6, bend_iii=0.2))
        seen.append(server.progress())
        ctx.feed.push(view(6.0, bend_iv=-0.8, bend_iii=0.4))
    monkeypatch.setattr(TwoSteps, 'on_wait', staticmethod(look))
    assert server.run(Goal()).status == SUCCEEDED
    progress = seen[0]
    assert progress.primitive == 'clamp rear' and progress.elapsed == pytest.approx(1.5)
    assert progress.timeout == 15.0
    assert progress.guard.joints == ['bend_iv', 'bend_iii']
    assert progress.guard.values == [-0.6, 0.2]
    assert progress.guard.thresholds == [-0.77, 0.35]
    assert server.progress() is None                # nothing runs after the goal
    assert server.trace.steps[-1].outcome == REACHED


def test_a_new_goal_starts_a_new_trace(rig, monkeypatch):
    server, feed = rig
    monkeypatch.setattr(TwoSteps, 'on_wait', staticmethod(
        lambda ctx: ctx.feed.push(view(4.0, bend_iv=-0.8))))
    server.run(Goal())
    first = list(server.trace.steps)
    feed.push(view(10.0))
    assert server.reserve(Goal()) is None
    server.run(Goal())
    assert len(server.trace.steps) == len(first) and server.trace.steps[0].start == 10.0


def test_trace_ends_one_step_at_a_time():
    trace = Trace()
    trace.end(1.0, REACHED)                 # nothing runs: no-op
    trace.start('a', 'g', 1.0)
    trace.start('b', 'g', 2.0)              # a start ends the one before
    trace.end(3.0, 'aborted')
    trace.end(4.0, REACHED)                 # already ended
    assert [(s.name, s.end, s.outcome) for s in trace.steps] == [('a', 2.0, REACHED), ('b', 3.0, 'aborted')]
    assert trace.running is None


def test_guard_numbers_of_each_guard_text():
    angles = dict.fromkeys(JOINTS, 0.0)
    angles.update(front_tilt=0.2, rotation=0.13)
    assert guard_numbers('front_tilt >= 0.400', angles) == (['front_tilt'], [0.2], [0.4])
    numbers = guard_numbers('|rotation - 0.100| <= 0.0425', angles)
    assert numbers.joints == ['rotation'] and numbers.thresholds == [0.0425]
    assert numbers.values[0] == pytest.approx(0.03)
    assert guard_numbers('no joint here', angles) == ([], [], [])
