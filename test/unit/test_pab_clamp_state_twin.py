"""Against the physics twin: "clamped" means pressing the wall.

A Clamp Straight cancelled after the rear outer bend passed its guard but
before the V reached the wall left, on main, angles that read as clamped:
the retry skipped the rear clamp and succeeded with the rear short of the
wall, and the server would have accepted a Drive. Now the server reports
the rear partly clamped, refuses Drive, and the retry clamps the rear until
its spring presses the wall (ground truth, read by the test only).
"""
import threading

import pytest

from pirate.testing.harness import SimHarness
from test_sequencer_sim import run_bounded
from test_sim_twin_sequencer import CLAMP_STRAIGHT, assert_clamped_straight, robot_wait

DRIVE = 4
REAR_GUARD = -0.77          # config/guards_90.yaml, clamp outer


def test_cancel_past_the_guard_short_of_the_wall_then_retry():
    with SimHarness(world='straight_90') as h:
        goal = h.goal(CLAMP_STRAIGHT)
        assert h.server.reserve(goal) is None
        done = {}
        h.when(lambda: h.feed.latest().angles['bend_iv'] <= REAR_GUARD - 0.005, h.server.cancel)
        worker = threading.Thread(target=lambda: done.update(o=h.execute_reserved(goal)), daemon=True)
        worker.start()
        worker.join(30.0)
        assert done['o'].status == 'preempted'
        robot_wait(h, 1.0)
        view = h.feed.latest()
        assert view.angles['bend_iv'] <= REAR_GUARD      # the angle alone would say clamped
        assert 26 not in h.ground_truth()['wheel_contacts']     # rear apex short of the wall
        assert 'rear partly clamped' in h.server.status()
        reason, _ = h.execute(h.goal(DRIVE, distance=50.0, speed=50.0))
        assert reason and 'clamped' in reason
        reason, outcome = h.execute(h.goal(CLAMP_STRAIGHT))
        assert reason is None and outcome.status == 'succeeded', outcome.message
        assert 'clamp rear' in h.prims.executed
        assert_clamped_straight(h)
        assert h.server.status() == 'Idle Clamped'


@pytest.mark.parametrize('front_outer', [-0.1, -0.5, -0.9])
def test_cancel_with_the_rear_clamped_then_retry_keeps_the_rear(front_outer):
    # Cancelled while clamping the front: the rear is clamped and held by its
    # worms at PWM 0. The retry must not let it go (torque mode at setpoint 0
    # did: the goal "succeeded" with the rear apex off the wall).
    with SimHarness(world='straight_90') as h:
        goal = h.goal(CLAMP_STRAIGHT)
        assert h.server.reserve(goal) is None
        h.when(lambda: h.prims.executed[-1:] == ['clamp front'] and h.feed.latest().angles['bend_i'] <= front_outer,
               h.server.cancel)
        worker = threading.Thread(target=h.execute_reserved, args=(goal,), daemon=True)
        worker.start()
        worker.join(30.0)
        assert 'rear full' in h.server.status()
        reason, outcome = run_bounded(h, goal)
        assert reason is None and outcome.status == 'succeeded', outcome.message
        assert 'clamp rear' not in h.prims.executed
        assert_clamped_straight(h)
