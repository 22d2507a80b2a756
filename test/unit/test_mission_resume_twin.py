"""A mission whose executive dies, taken up from its log by a new
executive, on the physics twin in one process (SimHarness, the real
Pirate Server; pirate.supervisory.resume): dead mid-Drive, the Drive goes
on for what was left; dead half round a bend, the turn goes on; dead once
the front crossed a T-joint, resume is refused and the robot stays held.

The death, at a robot instant (``SimHarness.when``): the log is read as it
stands then (written and flushed as it goes), and the Drive is cancelled
as the manager cancels the goal of an owner that is gone. The old
executive is then left to end on its own; the new one knows only the log
and the robot's odometry. Judged by the twin's ground truth."""
import threading

import pytest

from pirate.sequencer.pabs import junction
from pirate.supervisory import executive as ex
from pirate.supervisory import mission_log, planner
from pirate.supervisory.localiser import Localiser
from pirate.supervisory.resume import CannotResume, take_up
from pirate.testing.harness import SimHarness
from pirate.testing.harness_robot import HarnessRobot
from pirate.testing.truth import robot_along_m
from pirate.world import network

from test_executive_twin import MAX_DRIVE_MM, SETTINGS, UPRIGHT, finished, run_in_thread
from test_sequencer_sim import SAFE_INDICES

GOAL = {'map': 'straight_90', 'points': ['pit', 'target'], 'speed': 0.0, 'level': 'full', 'no_home': False,
        'policy': ''}
DIED_AFTER_MM = 200.0       # of the 500 mm Drive


def plan_of(goal):
    return planner.plan(network.load(network.world_path(goal['map'])), list(goal['points']), SETTINGS,
                        MAX_DRIVE_MM, goal['speed'] or None, not goal['no_home'])


def dies_when(h, path, condition):
    """Have the executive "die" at the first cycle where ``condition()``
    holds: the records then (a list, filled when it happens) and an Event
    set after."""
    records, died = [], threading.Event()

    def death():
        records.extend(mission_log.read(path))
        h.server.cancel()                       # the manager, for a goal whose owner is gone
        died.set()
    h.when(condition, death)
    return records, died


def drive_moved(h, mm):
    """A condition: the Drive running has moved ``mm``."""
    start = []

    def moved():
        if h.server.active != 'DRIVE':
            return False
        start.append(h.feed.latest().odometry)
        return h.feed.latest().odometry - start[0] >= mm
    return moved


def died_and_taken_up(h, path, goal, condition):
    """Run ``goal`` on ``h`` (its log at ``path``) until the executive dies
    at ``condition``, then take the mission up from the log with a new
    executive: (the Resume, the new robot, the new executive's Outcome)."""
    records, died = dies_when(h, path, condition)
    log = mission_log.MissionLog(path)
    pipe_map = network.load(network.world_path(goal['map']))
    old = ex.Executive(plan_of(goal), HarnessRobot(h), Localiser(pipe_map.points[goal['points'][0]], SETTINGS),
                       SETTINGS, out=lambda line: None, journal=log.write, goal=goal, name=goal['map'])
    old_outcome = finished(old, *run_in_thread(old))
    assert died.is_set() and old_outcome.status == 'cancelled', old_outcome.log
    robot = HarnessRobot(h)
    resume = take_up(records, plan_of, SETTINGS, robot.odometry_mm())
    new = ex.Executive(resume.plan, robot, resume.localiser, SETTINGS, out=lambda line: None,
                       journal=log.write, goal=resume.goal, entry=resume.entry, name=resume.mission)
    return resume, robot, finished(new, *run_in_thread(new))


def test_a_mission_whose_executive_died_mid_drive_is_taken_up_from_its_log_and_ends_at_its_target(tmpdir):
    path = str(tmpdir.join('mission_log.jsonl'))
    pipe_map = network.load(network.world_path('straight_90'))
    with SimHarness(world='straight_90', orientation=UPRIGHT + 0.1, seed=7) as h:
        died_at = []
        moved = drive_moved(h, DIED_AFTER_MM)
        resume, robot, outcome = died_and_taken_up(
            h, path, GOAL, lambda: moved() and not died_at.append(robot_along_m(pipe_map, h.ground_truth())))
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    assert resume.entry == ex.Entry(1, True, False), resume.message
    assert outcome.status == 'succeeded', outcome.log
    assert [g.step.pab for g in robot.goals] == ['DRIVE', 'HOME']          # the clamp had succeeded
    left_mm = robot.goals[0].step.distance_mm
    assert 500.0 - DIED_AFTER_MM - 30.0 < left_mm < 500.0 - DIED_AFTER_MM + 5.0, left_mm    # only what was left
    assert pipe_map.points['pit'] + 0.1 < died_at[0] < pipe_map.points['target'] - 0.2, died_at
    # the twin's wheels travel less than they count (measurements.md#twin-odometry): at least 80 % of the way
    assert 0.4 <= truth_m - pipe_map.points['pit'] <= 0.52, truth_m
    assert mission_log.last_ending(mission_log.read(path)).status == 'succeeded'


def test_a_mission_whose_executive_died_half_round_a_bend_goes_on_round_it_and_ends_at_its_target(tmpdir):
    """inspection_90, launch_pit -> after_bend, the executive dead with the
    middle swinging round the bend: the turn is sent again as it is (no
    re-clamp, which would undo it) and goes on from where the robot is."""
    pipe_map = network.load(network.world_path('inspection_90'))
    goal = dict(GOAL, map='inspection_90', points=['launch_pit', 'after_bend'])
    with SimHarness(world='inspection_90', orientation=UPRIGHT) as h:
        resume, robot, outcome = died_and_taken_up(
            h, str(tmpdir.join('mission_log.jsonl')), goal,
            lambda: h.server.active == 'MITRE_BEND' and h.server.pab_state == junction.SWINGING_MIDDLE)
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    assert resume.entry == ex.Entry(2, True, True), resume.message
    assert outcome.status == 'succeeded', outcome.log
    assert [g.step.pab for g in robot.goals] == ['MITRE_BEND', 'DRIVE', 'HOME'], outcome.log
    assert abs(truth_m - pipe_map.points['after_bend']) < 0.05, (truth_m, outcome.log)


def test_a_mission_whose_executive_died_mid_crossing_is_not_taken_up_and_the_robot_stays_held(tmpdir):
    """inspection_tee_90, the executive dead once the front had crossed the
    T-joint: a crossing cannot be resumed; resume is refused with that
    reason and nothing more is sent."""
    path = str(tmpdir.join('mission_log.jsonl'))
    goal = dict(GOAL, map='inspection_tee_90', points=['launch_pit', 'target'])
    with SimHarness(world='inspection_tee_90', orientation=UPRIGHT) as h:
        records, died = dies_when(h, path, lambda: h.server.active == 'T_JOINT'
                                  and h.server.pab_state == junction.CLAMPING_FRONT)
        pipe_map = network.load(network.world_path(goal['map']))
        old = ex.Executive(plan_of(goal), HarnessRobot(h), Localiser(pipe_map.points['launch_pit'], SETTINGS),
                           SETTINGS, out=lambda line: None, journal=mission_log.MissionLog(path).write, goal=goal)
        assert finished(old, *run_in_thread(old)).status == 'cancelled' and died.is_set()
        with pytest.raises(CannotResume, match='step 3 .T_JOINT STRAIGHT.* the crossing may have begun'):
            take_up(records, plan_of, SETTINGS, HarnessRobot(h).odometry_mm())
        sent = h.wires['setpoint'].sent[-1][1]
    assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent      # the safe hold on the wire
