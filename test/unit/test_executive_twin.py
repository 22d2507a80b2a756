"""The mission executive against the physics twin, in one process (issue 11
"Done when"): a route on straight_90 planned, run by the executive on the
real Pirate Server (SimHarness, pirate.supervisory.harness_robot), ends at
its target; the twin's ground truth (read by the test only) says the robot
really went there. bench/mission_sweep runs the same over many start rolls
with sensor noise."""
import math

from pirate.sim.harness import SimHarness
from pirate.supervisory import executive as ex
from pirate.supervisory import planner
from pirate.supervisory.harness_robot import HarnessRobot
from pirate.supervisory.localiser import Localiser
from pirate.supervisory.plan_cli import load_settings
from pirate.supervisory.truth import robot_along_m
from pirate.world import network

SPEEDUP = 30.0


def test_a_route_on_the_twin_runs_to_its_target_and_homes():
    settings, max_drive_mm = load_settings()
    pipe_map = network.load(network.world_path('straight_90'))
    plan = planner.plan(pipe_map, ['pit', 'target'], settings, max_drive_mm, None, True)
    with SimHarness(speedup=SPEEDUP, world='straight_90', orientation=math.pi / 2 + 0.1, seed=7) as h:
        start_m = robot_along_m(pipe_map, h.ground_truth())
        robot = HarnessRobot(h)
        run = ex.Executive(plan, robot, Localiser(pipe_map.points['pit'], settings), settings,
                           out=lambda line: None)
        outcome = run.run()
        truth_m = robot_along_m(pipe_map, h.ground_truth())
        assert outcome.status == 'succeeded', outcome.log
        assert [g.step.pab for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'HOME']
        assert not robot.clamped()                      # homed: unclamped at the target
    assert abs(start_m - pipe_map.points['pit']) < 0.01
    # 500 mm asked by odometry; the twin's wheels travel less than they count
    # (notes/issue-11.md): the robot really moved, at least 80 % of the way.
    assert 0.4 <= truth_m - start_m <= 0.52
    assert run.localiser.along_m >= pipe_map.points['target'] - 0.05
