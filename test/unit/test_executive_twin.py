"""The mission executive against the physics twin, in one process: routes
planned, run by the executive on the real Pirate Server (SimHarness, pirate.supervisory.harness_robot). The twin's ground
truth is read by the test only, to judge; the executive never sees it.
bench/mission_sweep runs the same over many start rolls with sensor noise.

- a straight route ends at its target;
- a route through a T-joint (clamp, drive, T_JOINT STRAIGHT, drive, home)
  re-anchors the estimate where the front V met the T-joint;
- a map that disagrees with the pipe (a T-joint sensed far from where the
  map has it; none where the map has one) stops the mission safe with the
  reason; one 300 mm further on than the map says is searched for only as
  far as the map and the localiser's tolerance allow, and the mission stops
  before the robot reaches it;
- a pause during the T-joint holds the robot safe; resume goes on from
  where the robot is;
- a pause half round a bend: resume sends the turn again as it is and it
  goes on from where the robot is;
- a route through two mitre bends and a T-joint (inspection_network_90)
  ends at its target, re-anchored at each junction;
- a route from a main into the branch of a T-joint entered through its run
  (tee_run_branch_left_90 with points) ends at its target in the branch;
- a route straight past a T-joint open to a side (tee_run_right_90 with
  points) drives past it clamped straight, every module past it;
- inspection_90 to past_tee: a mitre bend after a 1.5 m drive clamped
  sideways (which rolls the robot out of the straight band), then the
  T-joint open to the right driven past, without a retry;
- there and back: launch pit -> past the T-joint -> launch pit on
  inspection_network_90, the T-joint and the bend taken rear first on the
  way back, ends at the launch pit;
- there and back through inspection_90's bend: the rear slips on the bend's
  far wall on the way back, and the search allows it.
"""
import math
import re
import threading

import pytest
import yaml

from pirate.sequencer.pabs import junction
from pirate.testing.harness import SimHarness
from pirate.supervisory import executive as ex
from pirate.supervisory import planner
from pirate.testing.harness_robot import HarnessRobot
from pirate.supervisory.localiser import Localiser, searched_mm
from pirate.supervisory.plan_cli import load_settings
from pirate.testing.truth import middle, on_each_pab_state, on_pab_state, robot_along_m
from pirate.testing.worlds import junction_moved
from pirate.world import network
from test_sequencer_sim import SAFE_INDICES

WAIT_S = 600.0              # wall bound of a whole mission on a loaded machine
UPRIGHT = math.pi / 2
TAKING = 'Taking T-joint'       # the server state of T_JOINT (Fig 4.2)
SETTINGS, MAX_DRIVE_MM = load_settings()


def executive(plan, h, start_m, settings=SETTINGS, progress=None):
    robot = HarnessRobot(h)
    return robot, ex.Executive(plan, robot, Localiser(start_m, settings), settings, progress=progress,
                               out=lambda line: None)


def paused_on(h, plan, start_m, server_state, pab_state):
    """An executive on ``h`` that is paused once the server is in
    ``server_state`` with its PAB in ``pab_state``, and not yet running:
    (robot, run, the Event set when the mission waits for resume)."""
    paused = threading.Event()
    robot, run = executive(plan, h, start_m,
                           progress=lambda p: p.waiting_for.startswith(ex.WAIT_RESUME) and paused.set())
    on_pab_state(h, server_state, pab_state, lambda: threading.Thread(target=run.pause, args=('test',)).start())
    return robot, run, paused


def run_in_thread(run):
    out = {}
    worker = threading.Thread(target=lambda: out.update(outcome=run.run()), daemon=True)
    worker.start()
    return worker, out


def finished(run, worker, out):
    worker.join(WAIT_S)
    if worker.is_alive():
        run.cancel()
        worker.join(30.0)
        pytest.fail('the mission did not end within %.0f s wall; log: %s' % (WAIT_S, run.log[-5:]))
    return out['outcome']


def test_a_route_on_the_twin_runs_to_its_target_and_homes():
    pipe_map = network.load(network.world_path('straight_90'))
    plan = planner.plan(pipe_map, ['pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    with SimHarness(world='straight_90', orientation=UPRIGHT + 0.1, seed=7) as h:
        start_m = robot_along_m(pipe_map, h.ground_truth())
        robot, run = executive(plan, h, pipe_map.points['pit'])
        outcome = run.run()
        truth_m = robot_along_m(pipe_map, h.ground_truth())
        assert outcome.status == 'succeeded', outcome.log
        assert [g.step.pab for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'HOME']
        assert not robot.clamped()                      # homed: unclamped at the target
    assert abs(start_m - pipe_map.points['pit']) < 0.01
    # 500 mm asked by odometry; the twin's wheels travel less than they count
    # (measurements.md#twin-odometry): the robot really moved, at least 80 % of the way.
    assert 0.4 <= truth_m - start_m <= 0.52
    assert run.localiser.along_m >= pipe_map.points['target'] - 0.05


def test_a_route_through_a_t_joint_reanchors_where_the_front_v_met_it():
    """inspection_tee_90: launch_pit -> target through tee_1 (open upward).
    The estimate is re-anchored where the map puts the robot when its front
    V senses the T-joint; the twin's truth at that moment (the PAB stops
    its wheels) must agree within 50 mm; the robot ends past the T-joint."""
    pipe_map = network.load(network.world_path('inspection_tee_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    planner.check_runnable(plan)
    tee = planner.junctions(pipe_map)[0]
    with SimHarness(world='inspection_tee_90', orientation=UPRIGHT - 0.1, seed=3) as h:
        at_sensing = []
        on_pab_state(h, TAKING, junction.STOPPING,
                     lambda: at_sensing.append(robot_along_m(pipe_map, h.ground_truth())))
        robot, run = executive(plan, h, pipe_map.points['launch_pit'])
        outcome = finished(run, *run_in_thread(run))
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    assert outcome.status == 'succeeded', outcome.log
    assert [g.step.pab for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT', 'DRIVE', 'HOME']
    fix = run.localiser.fixes[0]
    assert fix.junction == 'tee_1' and abs(fix.mapped_m - at_sensing[0]) < 0.05, (fix, at_sensing)
    assert truth_m > tee.exit_m + 0.1, truth_m


def test_a_route_through_two_turns_and_a_t_joint_ends_at_its_target():
    """inspection_network_90 (mitre left, T-joint
    straight on, mitre right): the clamps each junction needs in between,
    every junction re-anchored where the twin's robot was when its PAB
    sensed it (within 50 mm), and the estimate at the target within 50 mm
    of the truth (the turns re-anchor where they end)."""
    pipe_map = network.load(network.world_path('inspection_network_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    planner.check_runnable(plan)
    with SimHarness(world='inspection_network_90', orientation=UPRIGHT + 0.15, seed=5) as h:
        robot, run = executive(plan, h, pipe_map.points['launch_pit'])
        at_sensing = {}
        on_each_pab_state(h, junction.SENSED_STATES, lambda: at_sensing.__setitem__(
            len(run.localiser.fixes), robot_along_m(pipe_map, h.ground_truth())))
        outcome = finished(run, *run_in_thread(run))
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    assert outcome.status == 'succeeded', outcome.log
    assert [g.step.pab for g in robot.goals] == [
        'CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT', 'CLAMP_SIDEWAYS', 'DRIVE',
        'MITRE_BEND', 'DRIVE', 'HOME']
    fixes = run.localiser.fixes
    assert [f.junction for f in fixes] == ['mitre_1', 'tee_1', 'mitre_2']
    assert all(abs(f.mapped_m - at_sensing[i]) < 0.05 for i, f in enumerate(fixes)), (fixes, at_sensing)
    assert abs(run.localiser.along_m - truth_m) < 0.05, (run.localiser.along_m, truth_m)


#: The one-T-joint worlds' T-joint ends 800 + 90 mm along the path (config/worlds/tee_run_*_90.yaml).
TEE_EXIT_MM = 800 + 90


def past_one_tee(world, seed):
    """A mission on ``world`` (a one-T-joint world) from its start ('pit') to a
    target 500 mm past the T-joint: (map, robot, run, outcome, ground truth)."""
    with open(network.world_path(world)) as stream:
        layout = yaml.safe_load(stream)
    pipe_map = network.build(dict(layout, points=[{'name': 'pit', 'at_mm': layout['start']['at_mm']},
                                                  {'name': 'target', 'at_mm': TEE_EXIT_MM + 500}]))
    plan = planner.plan(pipe_map, ['pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    planner.check_runnable(plan)
    with SimHarness(world=world, orientation=UPRIGHT + 0.1, seed=seed) as h:
        robot, run = executive(plan, h, pipe_map.points['pit'])
        outcome = finished(run, *run_in_thread(run))
        return pipe_map, robot, run, outcome, h.ground_truth()


def test_a_route_from_the_main_into_a_branch_ends_at_its_target_in_the_branch():
    """tee_run_branch_left_90 (the T-joint entered through its run, left by
    its branch to the left) with a pit and a target 500 mm into the branch:
    Clamp Sideways LEFT, T_JOINT LEFT, the robot's middle really in the
    branch at the end (ground truth) and the estimate, re-anchored where the
    turn ends, within 50 mm of the truth."""
    pipe_map, robot, run, outcome, truth = past_one_tee('tee_run_branch_left_90', seed=11)
    assert outcome.status == 'succeeded', outcome.log
    assert [(g.step.pab, g.step.option) for g in robot.goals] == [
        ('CLAMP_SIDEWAYS', 'LEFT'), ('DRIVE', None), ('T_JOINT', 'LEFT'), ('DRIVE', None), ('HOME', None)]
    assert middle(truth)[1] > 0.045 + 0.2, middle(truth)     # well into the branch, left of the main's wall
    assert abs(run.localiser.along_m - robot_along_m(pipe_map, truth)) < 0.05


def shifted_map(first_mm, target_mm):
    """tee_run_up_90's layout (tee open upward) with its first straight
    ``first_mm`` long: a map of that world that puts the T-joint elsewhere."""
    return network.build({'name': 'wrong_map', 'diameter_mm': 90, 'pieces': [
        {'type': 'straight', 'length_mm': first_mm}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
        {'type': 'straight', 'length_mm': 1500}, {'type': 'cap'}],
        'points': [{'name': 'pit', 'at_mm': 370}, {'name': 'target', 'at_mm': target_mm}]})


@pytest.mark.parametrize('world, first_mm, settings, reason, aborted', [
    # The pipe's T-joint is 280 mm before the map's: sensed too early; the PAB
    # took it (and ended clamped), then the executive stops.
    ('tee_run_up_90', 1080, SETTINGS, r'tee_1 found with the robot at \d+ mm, the map has it at 980 mm', False),
    # The map has a T-joint where the pipe is straight: searched 250 mm, none;
    # the PAB aborted into the safe hold, still clamped.
    ('straight_90', 800, dict(SETTINGS, search_mm=250), r'tee_1 not found within 250 mm', True),
], ids=['junction where the map has none', 'none where the map has one'])
def test_a_map_that_disagrees_with_the_pipe_stops_the_mission_safe(world, first_mm, settings, reason, aborted):
    pipe_map = shifted_map(first_mm, first_mm + 600)
    plan = planner.plan(pipe_map, ['pit', 'target'], settings, MAX_DRIVE_MM, None, True)
    with SimHarness(world=world, orientation=UPRIGHT) as h:
        robot, run = executive(plan, h, pipe_map.points['pit'], settings)
        outcome = finished(run, *run_in_thread(run))
        sent = h.wires['setpoint'].sent[-1][1]
        status_now = h.server.status()
    assert outcome.status == 'mismatch' and re.search(reason, outcome.message), outcome.log
    assert outcome.message in outcome.log[-1]                              # the reason is in the log
    assert [g.step.pab for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT']   # nothing after it
    assert robot.goals[-1].status == ('aborted' if aborted else 'succeeded')
    if aborted:
        assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent     # the safe hold on the wire
    assert status_now == 'Idle Clamped'                                    # held in the pipe, not let go


def test_a_t_joint_further_on_than_the_map_says_stops_the_mission_before_the_robot_reaches_it(tmp_path):
    """inspection_tee_90's map, the pipe's T-joint 300 mm further on: the
    junction PAB searches only to where the map has the T-joint plus the
    localiser's uncertainty there (less than the plan's search_mm), finds
    nothing there and the mission stops with the robot held clamped in the
    safe hold, still looking (nothing crossed, nothing opened), short of the
    real T-joint, the reason naming where it looked."""
    pipe_map = network.load(network.world_path('inspection_tee_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    tee = planner.junctions(pipe_map)[0]
    with SimHarness(world=junction_moved('inspection_tee_90', 300, str(tmp_path)), orientation=UPRIGHT,
                    seed=3) as h:
        at_search, states = [], []
        on_pab_state(h, TAKING, junction.SEARCHING, lambda: at_search.append(h.feed.latest().odometry))
        on_each_pab_state(h, set(junction.MACHINE.states), lambda: states.append(h.server.pab_state))
        robot, run = executive(plan, h, pipe_map.points['launch_pit'])
        outcome = finished(run, *run_in_thread(run))
        travelled_mm = h.feed.latest().odometry - at_search[0]
        truth_m = robot_along_m(pipe_map, h.ground_truth())
        sent = h.wires['setpoint'].sent[-1][1]
        status_now = h.server.status()
    search = run.search
    bound_mm = searched_mm(search)
    assert outcome.status == 'mismatch', outcome.log
    assert [g.step.pab for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT']      # nothing after it
    assert robot.goals[-1].step.distance_mm == pytest.approx(bound_mm) and bound_mm < SETTINGS['search_mm']
    assert search.to_m == pytest.approx(search.expected_m + search.uncertainty_m)         # the map + tolerance
    assert travelled_mm <= bound_mm + 10.0, (travelled_mm, bound_mm)         # two Mega cycles at 50 mm/s
    assert states[-1] == junction.SEARCHING, states                                      # it never went on
    assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent                        # the safe hold on the wire
    assert status_now == 'Idle Clamped'
    # the pipe's T-joint (300 mm on) would have been sensed with the middle 100 mm before it
    assert truth_m < tee.entry_m + 0.3 - 0.1, truth_m
    assert re.search(r'tee_1 not found within %.0f mm: the map has it at 1200 mm \(the robot\'s middle at 1100 mm '
                     r'when it senses it\); searched from %.0f to %.0f mm along the map, the estimate within %.0f mm'
                     % (bound_mm, search.from_m * 1000, search.to_m * 1000, search.uncertainty_m * 1000),
                     outcome.message), outcome.message


def test_a_bend_further_on_than_the_map_says_stops_the_steering_where_the_map_bounds_it(tmp_path):
    """bend_left_90's map (a pit at the start, a target 500 mm past the bend),
    the pipe's bend 300 mm further on: the turn steers only to where the map
    has the bend plus the localiser's uncertainty there (its steering
    allowance past the search is not added), its front not round any corner
    there; the mission stops in the safe hold before the turn proper (no
    clamp at a corner, the middle short of the real bend), the reason
    naming where it looked."""
    with open(network.world_path('bend_left_90')) as stream:
        layout = yaml.safe_load(stream)
    pipe_map = network.build(dict(layout, points=[{'name': 'pit', 'at_mm': layout['start']['at_mm']},
                                                  {'name': 'target', 'at_mm': 800 + 90 + 500}]))
    plan = planner.plan(pipe_map, ['pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    with SimHarness(world=junction_moved('bend_left_90', 300, str(tmp_path)), orientation=math.pi, seed=3) as h:
        at_steering, states = [], []
        on_pab_state(h, 'Taking Mitre bend', junction.STEERING_FRONT,
                     lambda: at_steering.append(h.feed.latest().odometry))
        on_each_pab_state(h, set(junction.MACHINE.states), lambda: states.append(h.server.pab_state))
        robot, run = executive(plan, h, pipe_map.points['pit'])
        outcome = finished(run, *run_in_thread(run))
        travelled_mm, bend_ii = h.feed.latest().odometry - at_steering[0], h.feed.latest().angles['bend_ii']
        steered_rad = float(h.server.book.for_diameter(90).row('turn')['steered_rad'])
        truth, sent = h.ground_truth(), h.wires['setpoint'].sent[-1][1]
    bound_mm = searched_mm(run.search)
    assert outcome.status == 'mismatch', outcome.log
    assert [g.step.pab for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND']    # nothing after it
    assert robot.goals[-1].step.distance_mm == pytest.approx(bound_mm) and bound_mm < SETTINGS['search_mm']
    assert travelled_mm <= bound_mm + 10.0, (travelled_mm, bound_mm)
    assert states[-1] == junction.STEERING_FRONT and junction.CLAMPING_AT_CORNER not in states, states
    assert bend_ii < steered_rad, bend_ii                                      # the front not round a corner
    assert middle(truth)[0] < (800 + 300) / 1000.0, middle(truth)             # short of the real bend
    assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent
    assert re.search(r'mitre_1 not found within %.0f mm: the map has it at 800 mm .*searched from %.0f to %.0f mm '
                     r'along the map, the estimate within %.0f mm' % (bound_mm, run.search.from_m * 1000,
                                                                     run.search.to_m * 1000,
                                                                     run.search.uncertainty_m * 1000),
                     outcome.message), outcome.message


@pytest.mark.parametrize('pause_in, resumed_pabs', [
    (junction.SEARCHING, ['T_JOINT', 'DRIVE', 'HOME']),
    (junction.CROSSING_FRONT, ['CLAMP_STRAIGHT', 'T_JOINT', 'DRIVE', 'HOME']),
    (junction.CLAMPING_FRONT, None),
], ids=['while looking for the T-joint', 'as the front starts across', 'after the front crossed'])
def test_a_pause_during_the_t_joint_holds_the_robot_safe_and_resume_goes_on_from_where_it_is(pause_in,
                                                                                          resumed_pabs):
    """Pause while T_JOINT STRAIGHT runs: its goal is cancelled and the safe
    hold is what stays on the wire. Before the T-joint was sensed, or just
    after (the front V not past it), the mission waits; resume re-clamps if
    the robot is no longer clamped and runs the same step again from where
    the robot is, which senses the T-joint and takes it; the route goes on.
    Paused after the front crossed, the crossing cannot be resumed: the
    mission stops with that reason, the robot held, nothing more sent."""
    pipe_map = network.load(network.world_path('inspection_tee_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'target'], SETTINGS, MAX_DRIVE_MM, None, True)
    with SimHarness(world='inspection_tee_90', orientation=UPRIGHT) as h:
        robot, run, paused = paused_on(h, plan, pipe_map.points['launch_pit'], TAKING, pause_in)
        worker, out = run_in_thread(run)
        if resumed_pabs is None:
            outcome = finished(run, worker, out)
        else:
            assert paused.wait(WAIT_S), run.log[-5:]
        sent = h.wires['setpoint'].sent[-1][1]
        assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent      # the safe hold on the wire
        assert not h.server.active and run.step_index == 2                  # held at the T-joint step
        assert robot.goals[-1].step.pab == 'T_JOINT' and robot.goals[-1].status == 'preempted'
        goals_at_pause = len(robot.goals)
        if resumed_pabs is not None:
            run.resume()
            outcome = finished(run, worker, out)
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    log = '\n'.join(outcome.log)
    if resumed_pabs is None:
        assert outcome.status == 'aborted' and 'cannot be resumed' in outcome.message, log
        assert len(robot.goals) == goals_at_pause, log                      # nothing sent after the pause
        return
    assert outcome.status == 'succeeded', log
    assert [g.step.pab for g in robot.goals[goals_at_pause:]] == resumed_pabs, log
    assert run.localiser.fixes[-1].junction == 'tee_1'
    assert truth_m > planner.junctions(pipe_map)[0].exit_m + 0.1, truth_m


@pytest.mark.parametrize('pause_in', [junction.SWINGING_MIDDLE, junction.DRIVING_IN])
def test_a_pause_half_round_a_bend_resumes_the_turn_where_it_is(pause_in):
    """Paused half round the first bend of inspection_90 (the middle swinging
    round, the front clamped in the new pipe; or driving into the new pipe,
    where the robot senses what it senses before a bend and the server's
    record of the turn decides): the safe hold on the wire; resume sends the
    turn again as it is, without a re-clamp (a Clamp Sideways there would
    undo the turn), the turn's PAB goes on from where the robot is, and the
    route ends at its target, judged by the twin's ground truth."""
    pipe_map = network.load(network.world_path('inspection_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'after_bend'], SETTINGS, MAX_DRIVE_MM, None, True)
    with SimHarness(world='inspection_90', orientation=UPRIGHT) as h:
        robot, run, paused = paused_on(h, plan, pipe_map.points['launch_pit'], 'Taking Mitre bend', pause_in)
        worker, out = run_in_thread(run)
        while not paused.wait(1.0) and worker.is_alive():      # a mission that ends instead of waiting
            pass
        assert paused.is_set(), run.log[-5:]
        sent = h.wires['setpoint'].sent[-1][1]
        assert all(sent[i] == 0 for i in SAFE_INDICES.values()), sent      # the safe hold on the wire
        assert robot.goals[-1].step.pab == 'MITRE_BEND' and robot.goals[-1].status == 'preempted'
        goals_at_pause = len(robot.goals)
        run.resume()
        outcome = finished(run, worker, out)
        truth_m = robot_along_m(pipe_map, h.ground_truth())
    log = '\n'.join(outcome.log)
    assert outcome.status == 'succeeded', log
    assert [g.step.pab for g in robot.goals[goals_at_pause:]] == ['MITRE_BEND', 'DRIVE', 'HOME'], log
    assert abs(truth_m - pipe_map.points['after_bend']) < 0.05, (truth_m, log)


def test_a_route_straight_past_a_t_joint_open_to_a_side_drives_past_it_clamped_straight():
    """tee_run_right_90 (entered through its run, the branch open to the
    right) with a pit at the start and a target 500 mm past the T-joint:
    Clamp Straight, one Drive past the T-joint (no junction PAB: upright no
    wheel meets the side hole, junctions.driven_past), a Drive on, Home.
    Judged by ground truth: every module past the T-joint's far edge, the
    estimate (nothing re-anchored) within 50 mm of the truth."""
    pipe_map, robot, run, outcome, truth = past_one_tee('tee_run_right_90', seed=13)
    assert outcome.status == 'succeeded', outcome.log
    assert [(g.step.pab, g.step.option) for g in robot.goals] == [
        ('CLAMP_STRAIGHT', None), ('DRIVE', None), ('DRIVE', None), ('HOME', None)]
    behind = [body for body, pose in truth['poses'].items() if pose[0][0] <= TEE_EXIT_MM / 1000.0]
    assert not behind, behind
    assert run.localiser.fixes == []
    assert abs(run.localiser.along_m - robot_along_m(pipe_map, truth)) < 0.05


def test_a_route_through_a_bend_after_a_long_drive_and_past_a_side_tee_needs_no_retry():
    """inspection_90, launch_pit -> past_tee: the 1485 mm drive clamped
    sideways LEFT rolls the twin's robot to about 3.04 rad, out of the
    straight band; Take mitre bend re-adjusts its clamp itself (before, it
    was rejected and the executive spent its retry re-clamping), then the
    T-joint open to the right is driven past clamped straight. The goals
    are the plan's, one each; every module ends past the T-joint."""
    pipe_map = network.load(network.world_path('inspection_90'))
    plan = planner.plan(pipe_map, ['launch_pit', 'past_tee'], SETTINGS, MAX_DRIVE_MM, None, True)
    planner.check_runnable(plan)
    tee = planner.junctions(pipe_map)[1]
    with SimHarness(world='inspection_90', orientation=UPRIGHT + 0.1, seed=17) as h:
        robot, run = executive(plan, h, pipe_map.points['launch_pit'])
        outcome = finished(run, *run_in_thread(run))
        truth = h.ground_truth()
    assert outcome.status == 'succeeded', outcome.log
    assert [(g.step.pab, g.step.option) for g in robot.goals] == [(s.pab, s.option) for s in plan.steps]
    assert [f.junction for f in run.localiser.fixes] == ['mitre_1']
    assert robot_along_m(pipe_map, truth) - pipe_map.points['past_tee'] < 0.05
    rear_along_m = robot_along_m(pipe_map, truth) - SETTINGS['robot']['rear_mm'] / 1000.0
    assert rear_along_m > tee.exit_m, (rear_along_m, tee)


def there_and_back(world, far_point, seed):
    """Launch pit -> ``far_point`` -> launch pit on ``world`` from upright:
    (map, robot, executive, outcome, the robot's true middle at the end, m along)."""
    pipe_map = network.load(network.world_path(world))
    plan = planner.plan(pipe_map, ['launch_pit', far_point, 'launch_pit'], SETTINGS, MAX_DRIVE_MM, None, True)
    planner.check_runnable(plan)
    with SimHarness(world=world, orientation=UPRIGHT, seed=seed) as h:
        robot, run = executive(plan, h, pipe_map.points['launch_pit'])
        outcome = finished(run, *run_in_thread(run))
        return pipe_map, robot, run, outcome, robot_along_m(pipe_map, h.ground_truth())


def test_a_mission_there_and_back_through_a_bend_and_a_t_joint_ends_at_the_launch_pit():
    """inspection_network_90 to its point past the T-joint: launch pit ->
    past the T-joint -> launch pit. On the way in the mitre bend LEFT and the
    T-joint (open upward) straight on front first; on the way back the
    T-joint and the bend rear first (negative search distances), re-anchored
    at each; the robot ends at the launch pit (ground truth within 100 mm:
    the last drive is by odometry from where the bend taken rear first ends)."""
    pipe_map, robot, run, outcome, truth_m = there_and_back('inspection_network_90', 'past_tee', seed=11)
    assert outcome.status == 'succeeded', outcome.log
    junction_goals = [(g.step.pab, g.step.option, g.step.distance_mm < 0) for g in robot.goals
                      if g.step.junction is not None]
    assert junction_goals == [('MITRE_BEND', 'LEFT', False), ('T_JOINT', 'STRAIGHT', False),
                              ('T_JOINT', 'STRAIGHT', True), ('MITRE_BEND', 'LEFT', True)]
    assert [f.junction for f in run.localiser.fixes] == ['mitre_1', 'tee_1', 'tee_1', 'mitre_1']
    assert abs(truth_m - pipe_map.points['launch_pit']) < 0.1, truth_m


def test_the_way_back_through_a_bend_whose_rear_slips_on_its_far_wall_ends_at_the_launch_pit():
    """inspection_90, launch pit -> after the bend -> launch pit: backing
    into the bend the rear pushes its far wall until it turns in, the wheels
    slipping (odometry about 1.5 times the travel); the bend was found on the
    way in, so the way back's search allows that slip (``steer_slip``) and the
    mission ends at the launch pit, its estimate there within 50 mm of the
    truth. Bounded as on the way in it stopped ``mismatch`` with the rear
    short of the bend."""
    pipe_map, robot, run, outcome, truth_m = there_and_back('inspection_90', 'after_bend', seed=23)
    assert outcome.status == 'succeeded', outcome.log
    assert [(g.step.pab, g.step.distance_mm < 0) for g in robot.goals if g.step.junction is not None] == [
        ('MITRE_BEND', False), ('MITRE_BEND', True)]
    assert abs(truth_m - pipe_map.points['launch_pit']) < 0.05, truth_m
    assert abs(run.localiser.along_m - truth_m) < 0.05, (run.localiser.along_m, truth_m)
