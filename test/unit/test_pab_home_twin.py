"""Home from any pose, in the physics twin.

Clamped straight, clamped sideways, partly clamped (a clamp cancelled
half way), front lifted only, a turn's steer left where it found no
opening: Home ends with both parts free (angles and
springs), lying on the pipe bottom (ground truth: the rotational module
back at the height and place where the free robot settled before the test
posed it, and no longer rolling), the rotation aligned, the front down and
the wheels stopped. A robot unclamped on its side stays on its side (the
twin, like the report's non-nominal starts: the modules rest on a flat).
The rotation at its limit is covered on the kinematic robot
(test_pab_rotation_limit.py): the twin's encoder starts at 0.
"""
import math
import threading

import pytest

from pirate.sequencer import clamp_state
from pirate.testing.harness import SimHarness
from pirate.sim.twin_robot import ROOT, ROTATIONAL_FRONT
from test_sequencer_sim import run_bounded
from test_sim_twin_sequencer import robot_wait

CLAMP_STRAIGHT, CLAMP_SIDEWAYS, MITRE_BEND, HOME, LEFT, RIGHT = 0, 1, 3, 5, 1, 2
REST_M = 0.006          # m: height of the free robot's resting place; Home leaves the bends
                        # at their open guards (up to 0.2 rad), not straight: a few mm of
                        # difference (clamped sideways, the centre sits 17 mm aside and 11 mm
                        # higher; after Home from sideways it rests 6.6 mm aside along the round
                        # floor, 0.9 mm higher): distance from the pipe axis and height are checked
SETTLED_RAD = 0.01      # rad of roll in 1 s: no longer rolling


def clamp(h, name, option=0):
    reason, outcome = run_bounded(h, h.goal(name, option=option))
    assert reason is None and outcome.status == 'succeeded', outcome.message


def partly(h):
    goal = h.goal(CLAMP_STRAIGHT)
    assert h.server.reserve(goal) is None
    worker = threading.Thread(target=h.execute_reserved, args=(goal,), daemon=True)
    worker.start()
    assert h.feed.wait_until(lambda v: v.angles['bend_iv'] < -0.4, 30.0, 'rear half clamped')
    h.server.cancel()
    worker.join(30.0)
    assert 'rear partly clamped' in h.server.status()


def steered(h):
    """A mitre LEFT sent in a straight pipe: it steers the front (the front
    module lifted toward the side, near move_front_turn), finds no opening
    within the goal's distance and aborts there."""
    clamp(h, CLAMP_SIDEWAYS, LEFT)
    reason, outcome = run_bounded(h, h.goal(MITRE_BEND, option=LEFT, distance=300.0))
    assert reason is None and outcome.status == 'aborted' and outcome.junction_missing, outcome.message
    assert h.feed.latest().angles['front_tilt'] > h.server.book.for_diameter(90).row('move_front_home')['above']


def lifted(h):
    h.prims.use(h.server.book.for_diameter(90))
    h.start_robot()
    h.prims.move_front('move_front')


START = {
    'clamped straight': (math.pi / 2, lambda h: clamp(h, CLAMP_STRAIGHT)),
    'clamped sideways': (0.0, lambda h: clamp(h, CLAMP_SIDEWAYS, RIGHT)),
    'partly clamped': (math.pi / 2, partly),
    'front lifted': (math.pi / 2, lifted),
    'steered, no opening': (math.pi / 2, steered),
}


@pytest.mark.parametrize('start', sorted(START))
def test_home_from_any_pose(start):
    roll, pose = START[start]
    with SimHarness(world='straight_90', orientation=roll) as h:
        robot_wait(h, 1.0)
        rest = h.model.body_pose(ROTATIONAL_FRONT)[0]
        pose(h)
        reason, outcome = run_bounded(h, h.goal(HOME))
        assert reason is None and outcome.status == 'succeeded', outcome.message
        robot_wait(h, 1.0)
        rolled = h.ground_truth()['roll']
        robot_wait(h, 1.0)
        view, guards = h.feed.latest(), h.server.book.for_diameter(90)
        assert clamp_state.sensed(guards, view) == (clamp_state.FREE, clamp_state.FREE), (view.angles, view.efforts)
        assert abs(h.ground_truth()['roll'] - rolled) < SETTLED_RAD
        home = h.model.body_pose(ROTATIONAL_FRONT)[0]
        assert abs(math.hypot(*home[1:]) - math.hypot(*rest[1:])) < REST_M, (rest, home)     # on the wall
        assert abs(home[2] - rest[2]) < REST_M, (rest, home)                                # at its bottom
        assert abs(view.angles['rotation']) <= guards.align_tolerance
        assert view.angles['front_tilt'] <= guards.move('move_front_down').guard
        assert abs(view.velocity) < 1.0
        assert h.server.status() == 'Idle Unclamped'


def test_home_after_a_turn_cancelled_while_steering_in_leaves_the_robot_loose():
    """A mitre LEFT cancelled 20 robot s in, its front steered into the bend,
    then Home: it succeeds, and nothing presses the wall harder than the
    robot's weight (ground truth: the wheels' normal forces). Lowering the
    front module into the opening pried the Bend I wheel on the wall with
    57 N (five times the weight) after a Home that read as unclamped; Home
    now leaves that front lifted and says so (bench/junction_turn_resume
    --then home)."""
    with SimHarness(world='bend_left_90', orientation=math.pi) as h:
        robot_wait(h, 1.0)
        clamp(h, CLAMP_SIDEWAYS, LEFT)
        goal = h.goal(MITRE_BEND, option=LEFT, distance=800.0)
        assert h.server.reserve(goal) is None
        worker = threading.Thread(target=h.execute_reserved, args=(goal,), daemon=True)
        worker.start()
        robot_wait(h, 20.0)
        h.server.cancel()
        worker.join(30.0)
        robot_wait(h, 2.0)
        reason, outcome = run_bounded(h, h.goal(HOME))
        assert reason is None and outcome.status == 'succeeded', outcome.message
        robot_wait(h, 1.0)
        model = h.model.model
        weight_n = float(model.body_subtreemass[model.body(ROOT).id]) * 9.81
        pressing_n = sum(h.ground_truth()['wheel_contacts'].values())
        view, guards = h.feed.latest(), h.server.book.for_diameter(90)
        assert pressing_n <= 1.25 * weight_n, (pressing_n, weight_n, outcome.message, view.angles)
        along = view.angles['bend_i'] <= guards.row('home_front_down')['bend_i_max_rad']
        lowered = view.angles['front_tilt'] <= guards.move('move_front_down').guard
        # Lowered only along the pipe; left lifted only for what Home senses:
        # Bend I past the bound, or the turn stopped steering into an opening here.
        assert along or not lowered, (outcome.message, view.angles)
        assert lowered or not along or 'stopped steering it into an opening' in outcome.message, outcome.message
        assert along or 'front module left lifted' in outcome.message, outcome.message
        assert clamp_state.sensed(guards, view) == (clamp_state.FREE, clamp_state.FREE), (view.angles, view.efforts)


def test_home_half_round_a_corner_is_refused_and_the_turn_re_sent_finishes_it():
    """A mitre LEFT cancelled once the front has turned into the new pipe
    (Bend II past the turn row's steered_rad, as the robot senses it): Home
    is refused before anything moves, naming the way out; the turn re-sent
    finishes, and Home then leaves the robot loose. Before, Home's unclamp
    pushed 15 s against the junction's walls and aborted (bench/
    junction_turn_resume --then home, cancels at 30 and 35 s)."""
    with SimHarness(world='bend_left_90', orientation=math.pi) as h:
        robot_wait(h, 1.0)
        clamp(h, CLAMP_SIDEWAYS, LEFT)
        turn, steered_rad = h.goal(MITRE_BEND, option=LEFT, distance=800.0), h.server.book.for_diameter(90).row(
            'turn')['steered_rad']
        assert h.server.reserve(turn) is None
        worker = threading.Thread(target=h.execute_reserved, args=(turn,), daemon=True)
        worker.start()
        assert h.feed.wait_until(lambda v: v.angles['bend_ii'] >= steered_rad, 120.0, 'the front turned in')
        h.server.cancel()
        worker.join(30.0)
        robot_wait(h, 2.0)
        before = dict(h.feed.latest().angles)
        reason, _ = run_bounded(h, h.goal(HOME))
        assert reason is not None and 're-send the turn toward the LEFT to finish it, then Home' in reason, reason
        robot_wait(h, 1.0)
        after = h.feed.latest().angles
        assert all(abs(after[j] - before[j]) < 0.02 for j in before), (before, after)
        reason, outcome = run_bounded(h, turn)
        assert reason is None and outcome.status == 'succeeded', reason or outcome.message
        reason, outcome = run_bounded(h, h.goal(HOME))
        assert reason is None and outcome.status == 'succeeded', reason or outcome.message
        view = h.feed.latest()
        assert clamp_state.sensed(h.server.book.for_diameter(90), view) == (clamp_state.FREE, clamp_state.FREE)
