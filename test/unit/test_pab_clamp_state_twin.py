"""Issue 10.1 against the physics twin: "clamped" means pressing the wall.

A Clamp Straight cancelled after the rear outer bend passed its guard but
before the V reached the wall left, on main, angles that read as clamped:
the retry skipped the rear clamp and succeeded with the rear short of the
wall, and the server would have accepted a Drive. Now the server reports
the rear partly clamped, refuses Drive, and the retry clamps the rear until
its spring presses the wall (ground truth, read by the test only).
"""
import threading

from pirate.sim.harness import SimHarness
from test_sim_twin_sequencer import CLAMP_STRAIGHT, assert_clamped_straight, robot_wait

DRIVE = 4
SPEEDUP = 5.0               # the V needs ~1 s of robot time from guard to wall: 200 ms of wall clock for the cancel
REAR_GUARD = -0.77          # config/guards_90.yaml, clamp outer


def test_cancel_past_the_guard_short_of_the_wall_then_retry():
    with SimHarness(speedup=SPEEDUP, world='straight_90') as h:
        goal = h.goal(CLAMP_STRAIGHT)
        assert h.server.reserve(goal) is None
        done = {}
        worker = threading.Thread(target=lambda: done.update(o=h.server.run(goal)), daemon=True)
        worker.start()
        assert h.feed.wait_until(lambda v: v.angles['bend_iv'] <= REAR_GUARD - 0.005, 30.0, 'rear past its guard')
        h.server.cancel()
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
