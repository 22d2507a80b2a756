"""A mission whose executive dies mid-Drive, taken up from its log by a
new executive, on the physics twin in one process (SimHarness, the real
Pirate Server; pirate.supervisory.resume).

The death, at a robot instant (``SimHarness.when``): the log is read as it
stands then (written and flushed as it goes), and the Drive is cancelled
as the manager cancels the goal of an owner that is gone. The old
executive is then left to end on its own; the new one knows only the log
and the robot's odometry. Judged by the twin's ground truth."""
import threading

from pirate.supervisory import executive as ex
from pirate.supervisory import mission_log, planner
from pirate.supervisory.localiser import Localiser
from pirate.supervisory.resume import take_up
from pirate.testing.harness import SimHarness
from pirate.testing.harness_robot import HarnessRobot
from pirate.testing.truth import robot_along_m
from pirate.world import network

from test_executive_twin import MAX_DRIVE_MM, SETTINGS, UPRIGHT, finished, run_in_thread

GOAL = {'map': 'straight_90', 'points': ['pit', 'target'], 'speed': 0.0, 'level': 'full', 'no_home': False,
        'policy': ''}
DIED_AFTER_MM = 200.0       # of the 500 mm Drive


def plan_of(goal):
    return planner.plan(network.load(network.world_path(goal['map'])), list(goal['points']), SETTINGS,
                        MAX_DRIVE_MM, goal['speed'] or None, not goal['no_home'])


def dies_mid_drive(h, path):
    """Have the executive "die" once the Drive moved DIED_AFTER_MM: the
    records then (a list, filled when it happens) and an Event set after."""
    records, died, start = [], threading.Event(), []

    def moved():
        if h.server.active != 'DRIVE':
            return False
        start.append(h.feed.latest().odometry)
        return h.feed.latest().odometry - start[0] >= DIED_AFTER_MM

    def death():
        records.extend(mission_log.read(path))
        h.server.cancel()                       # the manager, for a goal whose owner is gone
        died.set()
    h.when(moved, death)
    return records, died


def test_a_mission_whose_executive_died_mid_drive_is_taken_up_from_its_log_and_ends_at_its_target(tmpdir):
    path = str(tmpdir.join('mission_log.jsonl'))
    pipe_map = network.load(network.world_path('straight_90'))
    with SimHarness(world='straight_90', orientation=UPRIGHT + 0.1, seed=7) as h:
        records, died = dies_mid_drive(h, path)
        log = mission_log.MissionLog(path)
        old = ex.Executive(plan_of(GOAL), HarnessRobot(h), Localiser(pipe_map.points['pit'], SETTINGS), SETTINGS,
                           out=lambda line: None, journal=log.write, goal=GOAL, name='straight_90: pit -> target')
        old_outcome = finished(old, *run_in_thread(old))
        assert died.is_set() and old_outcome.status == 'cancelled', old_outcome.log
        died_m = robot_along_m(pipe_map, h.ground_truth())
        robot = HarnessRobot(h)
        resume = take_up(records, plan_of, SETTINGS, robot.odometry_mm())
        new = ex.Executive(resume.plan, robot, resume.localiser, SETTINGS, out=lambda line: None,
                           journal=log.write, goal=resume.goal, entry=resume.entry, name=resume.mission)
        outcome = finished(new, *run_in_thread(new))
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    assert resume.entry == ex.Entry(1, True, False), resume.message
    assert outcome.status == 'succeeded', outcome.log
    assert [g.step.pab for g in robot.goals] == ['DRIVE', 'HOME']          # the clamp had succeeded
    left_mm = robot.goals[0].step.distance_mm
    assert 500.0 - DIED_AFTER_MM - 30.0 < left_mm < 500.0 - DIED_AFTER_MM + 5.0, left_mm    # only what was left
    assert pipe_map.points['pit'] + 0.1 < died_m < pipe_map.points['target'] - 0.2, died_m
    # the twin's wheels travel less than they count (measurements.md#twin-odometry): at least 80 % of the way
    assert 0.4 <= truth_m - pipe_map.points['pit'] <= 0.52, truth_m
    assert mission_log.last_ending(mission_log.read(path)).status == 'succeeded'
