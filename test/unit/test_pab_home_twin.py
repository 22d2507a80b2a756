"""Home from any pose, in the physics twin (issue 10.4).

Clamped straight, clamped sideways, partly clamped (a clamp cancelled
half way), front lifted only: Home ends with both parts free (angles and
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
from pirate.sim.harness import SimHarness
from pirate.sim.twin_robot import ROTATIONAL_FRONT
from test_sequencer_sim import run_bounded
from test_sim_twin_sequencer import robot_wait

SPEEDUP = 10.0
CLAMP_STRAIGHT, CLAMP_SIDEWAYS, HOME, RIGHT = 0, 1, 5, 2
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
    worker = threading.Thread(target=h.server.run, args=(goal,), daemon=True)
    worker.start()
    assert h.feed.wait_until(lambda v: v.angles['bend_iv'] < -0.4, 30.0, 'rear half clamped')
    h.server.cancel()
    worker.join(30.0)
    assert 'rear partly clamped' in h.server.status()


def lifted(h):
    h.prims.use(h.server.book.for_diameter(90))
    h.start_robot()
    h.prims.move_front('move_front')


START = {
    'clamped straight': (math.pi / 2, lambda h: clamp(h, CLAMP_STRAIGHT)),
    'clamped sideways': (0.0, lambda h: clamp(h, CLAMP_SIDEWAYS, RIGHT)),
    'partly clamped': (math.pi / 2, partly),
    'front lifted': (math.pi / 2, lifted),
}


@pytest.mark.parametrize('start', sorted(START))
def test_home_from_any_pose(start):
    roll, pose = START[start]
    with SimHarness(speedup=SPEEDUP, world='straight_90', orientation=roll) as h:
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
