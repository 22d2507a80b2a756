"""A mission taken up from its log after its executive died
(pirate.supervisory.resume), against the scripted robot of test_executive.

The executive "dies" with a step running: the log is read as the death
leaves it (everything written so far, flushed), then the manager cancels
the dead owner's goal (the robot stops, held) and a new executive takes the
mission up from that log with the same robot."""
import json
import threading

import pytest

from pirate.supervisory import executive as ex
from pirate.supervisory import mission_log, planner
from pirate.supervisory.localiser import Localiser, restored, sensed_at_m
from pirate.supervisory.resume import CannotResume, interrupted, take_up
from pirate.world import network

from test_executive import MAP, SETTINGS, TEE_MAP, WAIT_S, FakeRobot, mission

GOAL = {'map': 'test', 'points': ['pit', 'target'], 'speed': 0.0, 'level': 'full', 'no_home': False, 'policy': ''}


def plan_on(world):
    return lambda goal: planner.plan(world, list(goal['points']), SETTINGS, 5000.0)


def died_during(robot, tmpdir, world=MAP, before_cancel=lambda: None):
    """Run a mission until ``robot``'s held step runs, read the log as a
    death then leaves it, then (after ``before_cancel()``) cancel the goal
    as the manager does for a dead owner and let the old executive finish:
    the log's records."""
    path = str(tmpdir.join('mission_log.jsonl'))
    log = mission_log.MissionLog(path)
    run = mission(robot, world=world, journal=log.write, goal=GOAL, name='test: pit -> target')
    thread = threading.Thread(target=run.run, daemon=True)
    thread.start()
    assert robot.entered.wait(WAIT_S)
    records = mission_log.read(path)
    before_cancel()
    robot.cancel()
    thread.join(WAIT_S)
    log.close()
    robot.goals = []
    return records


def resumed(records, robot, world=MAP):
    """A new executive taking the log's mission up with ``robot``: (Resume, Outcome)."""
    resume = take_up(records, plan_on(world), SETTINGS, robot.odometry())
    run = ex.Executive(resume.plan, robot, resume.localiser, SETTINGS, out=lambda line: None, goal=resume.goal,
                       entry=resume.entry, name=resume.mission)
    return resume, run.run()


def test_a_drive_interrupted_half_way_goes_on_for_what_is_left_and_the_mission_ends_at_the_target(tmpdir):
    robot = FakeRobot(0.3, hold_step='DRIVE')
    robot.clamped_after_cancel = True                   # the manager's cancel left it clamped, held
    records = died_during(robot, tmpdir)
    resume, outcome = resumed(records, robot)
    assert resume.entry == ex.Entry(1, True, False)
    assert 'step 2 of 5 (DRIVE), run again from where the robot is' in resume.message
    assert outcome.status == 'succeeded', outcome.log
    drive_mm = [g[2] for g in robot.goals if g[0] == 'DRIVE'][0]
    first_drive_mm = planner.plan(MAP, ['pit', 'target'], SETTINGS, 5000.0).steps[1].distance_mm
    assert drive_mm == pytest.approx(first_drive_mm / 2.0, abs=1.0)      # only what was left
    assert [g[0] for g in robot.goals] == ['DRIVE', 'MITRE_BEND', 'DRIVE', 'HOME']
    assert abs(robot.true_m - 3.0) < 1e-6


def test_steps_that_had_succeeded_are_not_run_again_and_an_unclamped_robot_is_re_clamped_first(tmpdir):
    robot = FakeRobot(0.3, hold_step='HOME')
    records = died_during(robot, tmpdir)
    resume, outcome = resumed(records, robot)
    assert resume.entry == ex.Entry(4, True, False) and outcome.status == 'succeeded'
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'HOME']


def test_a_turn_that_had_sensed_its_junction_is_re_sent_as_it_is(tmpdir):
    robot = FakeRobot(0.3, hold_step='MITRE_BEND')
    robot.sensed_then_moved_mm = 60.0
    records = died_during(robot, tmpdir)
    resume, outcome = resumed(records, robot)
    assert resume.entry == ex.Entry(2, True, True) and 're-sent as it is' in resume.message
    assert outcome.status == 'succeeded', outcome.log
    assert [g[0] for g in robot.goals] == ['MITRE_BEND', 'DRIVE', 'HOME']
    assert abs(robot.true_m - 3.0) < 1e-6


def test_a_crossing_that_may_have_begun_is_not_resumed(tmpdir):
    robot = FakeRobot(0.3, hold_step='T_JOINT')
    robot.sensed_then_moved_mm = 200.0                   # more than the T-joint's length
    records = died_during(robot, tmpdir, world=TEE_MAP)
    with pytest.raises(CannotResume, match='the crossing may have begun and cannot be resumed'):
        take_up(records, plan_on(TEE_MAP), SETTINGS, robot.odometry())


def test_a_crossing_that_moved_less_than_its_junction_runs_again_and_senses_it(tmpdir):
    """However early the T-joint was sensed, the front V has not passed it."""
    robot = FakeRobot(0.3, hold_step='T_JOINT')
    tee = planner.junctions(TEE_MAP)[0]

    def moved_50_mm():      # the held goal ends 50 mm on from where it started, short of sensing the T-joint
        robot.sensed_then_moved_mm = (robot.true_m + 0.05 - sensed_at_m(tee, 1, SETTINGS['robot'])) * 1000.0
    records = died_during(robot, tmpdir, world=TEE_MAP, before_cancel=moved_50_mm)
    resume, outcome = resumed(records, robot, world=TEE_MAP)
    assert resume.entry == ex.Entry(2, True, False) and 'the odometry moved 50 mm' in resume.message
    assert outcome.status == 'succeeded', outcome.log
    assert [f.junction for f in resume.localiser.fixes] == ['tee_1']


def test_the_estimate_goes_on_from_the_last_anchor_its_uncertainty_grown_by_the_odometry_since():
    localiser = Localiser(0.3, SETTINGS)
    localiser.update(100.0)
    localiser.update(600.0)
    state = localiser.state()
    assert state['along_mm'] == pytest.approx(800.0) and state['odometry_mm'] == 600.0
    again = restored(state, SETTINGS)
    assert again.along_m == pytest.approx(localiser.along_m)
    assert again.uncertainty_m(600.0) == pytest.approx(localiser.uncertainty_m(600.0))
    again.update(900.0)
    assert again.along_m == pytest.approx(1.1)
    assert again.uncertainty_m(900.0) - localiser.uncertainty_m(600.0) == pytest.approx(
        SETTINGS['odometry_drift'] * 0.3)


def test_a_restored_estimate_knows_the_junctions_found_so_the_way_back_allows_their_slip():
    """A junction found before the executive died is still found after:
    a turn back through it may count its steering's slip (pirate.supervisory.localiser)."""
    (mitre,) = planner.junctions(MAP)
    localiser = Localiser(1.0, SETTINGS)
    localiser.update(0.0)
    localiser.junction_found(mitre, (sensed_at_m(mitre, 1, SETTINGS['robot']) - 1.0) * 1000.0, 1)
    localiser.update(1500.0)
    again = restored(json.loads(json.dumps(localiser.state())), SETTINGS)
    assert [f.junction for f in again.fixes] == [mitre.name]
    assert again.search(mitre, -1, 5000.0) == localiser.search(mitre, -1, 5000.0)
    assert restored(dict(localiser.state(), found=[]), SETTINGS).search(mitre, -1, 5000.0).to_m > \
        localiser.search(mitre, -1, 5000.0).to_m                    # not found before: a shorter search back


def _log(*records):
    start = {'event': 'start', 'mission': 'm', 'steps': 5, 'goal': GOAL, 'first_step': 1,
             'localiser': Localiser(0.3, SETTINGS).state()}
    return [start] + list(records)


@pytest.mark.parametrize('records, reason', [
    ([], 'no mission in the log'),
    (_log({'event': 'end', 'status': 'succeeded', 'message': '5 PABs'}), r'ended: succeeded \(5 PABs\)'),
    ([{'event': 'start', 'mission': 'm', 'steps': 5}], 'does not say its goal and estimate'),
])
def test_a_log_without_an_interrupted_mission_is_refused_with_the_reason(records, reason):
    with pytest.raises(CannotResume, match=reason):
        take_up(records, plan_on(MAP), SETTINGS, 0.0)


def test_a_map_that_no_longer_loads_is_refused_with_the_reason():
    def gone(goal):
        return network.load(network.world_path('/nowhere/%s.yaml' % goal['map']))
    with pytest.raises(CannotResume, match='cannot be planned again: /nowhere/test.yaml: cannot read'):
        take_up(_log(), gone, SETTINGS, 0.0)


def test_a_map_that_now_plans_another_route_is_refused():
    with pytest.raises(CannotResume, match='now plans 5 steps, the log.s mission had 7'):
        take_up([dict(_log()[0], steps=7)], plan_on(MAP), SETTINGS, 0.0)


def test_an_unknown_odometry_or_one_moved_further_than_the_step_could_is_refused():
    started = _log({'event': 'step', 'step': 1, 'pab': 'CLAMP_SIDEWAYS', 'option': 'LEFT',
                    'localiser': dict(Localiser(0.3, SETTINGS).state(), odometry_mm=0.0, anchor_odometry_mm=0.0)})
    with pytest.raises(CannotResume, match='no robot state'):
        take_up(started, plan_on(MAP), SETTINGS, None)
    with pytest.raises(CannotResume, match='odometry moved 2000 mm since the log.s last estimate, more than step 1'):
        take_up(started, plan_on(MAP), SETTINGS, 2000.0)
    assert take_up(started, plan_on(MAP), SETTINGS, 10.0).entry == ex.Entry(0, True, False)


def test_the_log_says_where_the_mission_stood_step_by_step():
    state = Localiser(0.3, SETTINGS).state()
    assert interrupted(_log()).step == 0 and not interrupted(_log()).started
    began = _log({'event': 'step', 'step': 1, 'pab': 'CLAMP_SIDEWAYS', 'localiser': state})
    assert interrupted(began)[3:5] == (0, True)
    done = began + [{'event': 'step_end', 'step': 1, 'pab': 'CLAMP_SIDEWAYS', 'status': 'succeeded',
                     'localiser': dict(state, along_mm=301.0)}]
    assert interrupted(done)[3:6] == (1, False, dict(state, along_mm=301.0))


@pytest.mark.parametrize('moved_mm, turn_begun', [(10.0, False), (400.0, True)])
def test_a_turn_is_re_sent_as_it_is_only_once_it_may_have_sensed_its_junction(moved_mm, turn_begun):
    """The turn's step began 500 mm before where it senses the bend, within
    150 mm: moved 10 mm it cannot have; moved 400 mm it may have."""
    bend = planner.plan(MAP, ['pit', 'target'], SETTINGS, 5000.0).steps[2]
    sensed_mm = sensed_at_m(bend.junction, 1, SETTINGS['robot']) * 1000.0
    state = {'along_mm': sensed_mm - 500.0, 'anchor_mm': sensed_mm - 500.0, 'anchor_odometry_mm': 0.0,
             'odometry_mm': 0.0, 'uncertainty_mm': 150.0}
    began = _log({'event': 'step', 'step': 3, 'pab': 'MITRE_BEND', 'option': 'LEFT', 'localiser': state})
    resume = take_up(began, plan_on(MAP), SETTINGS, moved_mm)
    assert resume.entry == ex.Entry(2, True, turn_begun)
    assert resume.localiser.along_m * 1000.0 == pytest.approx(sensed_mm - 500.0 + moved_mm)
