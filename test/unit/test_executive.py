"""Mission executive and localisation (pirate.supervisory.executive,
.localiser) against a scripted robot that moves along the map.

The fake robot knows the true pipe (junctions possibly elsewhere than the
map says) and reports only what the real one would: odometry and where a
junction PAB found its junction. Threads meet on events, never on sleeps."""
import os
import threading

import pytest
import yaml

from pirate import paths
from pirate.sequencer.junctions import is_turn
from pirate.supervisory import executive as ex
from pirate.supervisory import planner
from pirate.supervisory.localiser import Fix, Localiser, MapMismatch, sensed_at_m
from pirate.world import network

with open(os.path.join(paths.CONFIG_DIR, 'supervisory.yaml')) as _f:
    SETTINGS = yaml.safe_load(_f)
WAIT_S = 10.0
MAP = network.build({'name': 'test', 'diameter_mm': 90, 'pieces': [
    {'type': 'straight', 'length_mm': 2000}, {'type': 'mitre', 'turn': 'left'},
    {'type': 'straight', 'length_mm': 2000}, {'type': 'cap'}],
    'points': [{'name': 'pit', 'at_mm': 300}, {'name': 'target', 'at_mm': 3000}]})
#: The same with a T-joint gone straight through (its side open upward) instead of the bend.
TEE_MAP = network.build({'name': 'test_tee', 'diameter_mm': 90, 'pieces': [
    {'type': 'straight', 'length_mm': 2000}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
    {'type': 'straight', 'length_mm': 2000}, {'type': 'cap'}],
    'points': [{'name': 'pit', 'at_mm': 300}, {'name': 'target', 'at_mm': 3000}]})


class FakeRobot(object):
    """Moves a true position along the path; junctions at their mapped place + ``shift_mm``."""

    def __init__(self, start_m, shift_mm=0.0, fail=None, hold_step=None):
        self.true_m, self.start_m, self.shift_m = start_m, start_m, shift_mm / 1000.0
        self.fail = dict(fail or {})          # pab -> list of statuses to return first
        self.goals = []
        self.hold_step = hold_step            # a pab that blocks until cancelled (once)
        self.clamped_after_cancel = False     # the server's word after that cancel
        self.sensed_then_moved_mm = None      # a held junction step: sensed its junction, moved this far
        self.entered, self._cancel = threading.Event(), threading.Event()
        self.is_clamped = True              # what the server says now (clamped())

    def clamped(self):
        return self.is_clamped

    def odometry(self):
        return (self.true_m - self.start_m) * 1000.0

    def cancel(self):
        self._cancel.set()

    def run(self, step):
        self.goals.append((step.pab, step.option, round(step.distance_mm)))
        if self.fail.get(step.pab):
            return ex.Report(self.fail[step.pab].pop(0), 'scripted', self.odometry(), None, False)
        if step.pab == self.hold_step:
            self.hold_step = None
            self.entered.set()
            assert self._cancel.wait(WAIT_S)
            self._cancel.clear()
            self.is_clamped = self.clamped_after_cancel
            if step.junction is not None and self.sensed_then_moved_mm is not None:
                self.true_m = sensed_at_m(step.junction, 1, SETTINGS['robot']) + self.sensed_then_moved_mm / 1000.0
                return ex.Report('preempted', 'cancelled', self.odometry(),
                                 self.odometry() - self.sensed_then_moved_mm, False)
            self.true_m += step.distance_mm / 2000.0
            return ex.Report('preempted', 'cancelled', self.odometry(), None, False)
        if step.pab == 'DRIVE':
            self.true_m += step.distance_mm / 1000.0
        found = None
        if step.junction is not None:
            sign = 1 if step.distance_mm > 0 else -1
            edge = sensed_at_m(step.junction, sign, SETTINGS['robot']) + self.shift_m
            if is_turn(step.junction.direction) and sign * (self.true_m - edge) > 0:
                self.true_m = step.end_m + self.shift_m     # a turn re-sent half round: it goes on, senses nothing
                return ex.Report('succeeded', 'resumed', self.odometry(), None, False)
            if abs(edge - self.true_m) * 1000 > abs(step.distance_mm):
                return ex.Report('aborted', 'no junction within %.0f mm' % abs(step.distance_mm),
                                 self.odometry() + step.distance_mm, None, True)
            self.true_m = edge
            found = self.odometry()
            self.true_m = step.end_m + self.shift_m
        self.is_clamped = step.pab != 'HOME'
        return ex.Report('succeeded', 'done', self.odometry(), found, False)


def mission(robot, route=('pit', 'target'), world=MAP, **kw):
    route_plan = planner.plan(world, list(route), SETTINGS, 5000.0)
    progress = kw.pop('progress', None)
    return ex.Executive(route_plan, robot, Localiser(world.points[route[0]], SETTINGS), SETTINGS,
                        progress=progress, out=lambda line: None, **kw)


def test_full_level_runs_the_route_and_ends_at_the_target():
    robot = FakeRobot(0.3, shift_mm=60)
    run = mission(robot)
    outcome = run.run()
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'DRIVE', 'HOME']
    # The junction re-anchored the estimate; the last drive went to where the robot really is.
    assert abs(run.localiser.fixes[0].estimated_m - run.localiser.fixes[0].mapped_m - 0.06) < 1e-6
    assert abs(robot.true_m - 3.0 - 0.06) < 1e-6 and abs(run.localiser.along_m - 3.0) < 1e-6


def test_a_turn_re_anchors_where_it_ends_whatever_its_odometry_counted_round_the_corner():
    """Round a corner the wheels slip (the twin over-counts ~250 mm): after a
    turn the estimate is where the turn leaves the robot, so the last drive
    still ends at the target."""
    robot = FakeRobot(0.3)
    take = robot.run

    def slipping(step):
        report = take(step)
        if step.pab == 'MITRE_BEND':
            robot.start_m -= 0.25                      # counted 250 mm the robot did not travel
            report = report._replace(odometry_mm=robot.odometry())
        return report
    robot.run = slipping
    run = mission(robot)
    assert run.run().status == 'succeeded'
    assert abs(robot.true_m - 3.0) < 1e-6 and abs(run.localiser.along_m - 3.0) < 1e-6


def test_an_abort_is_retried_after_reclamping_then_the_mission_goes_on():
    robot = FakeRobot(0.3, fail={'MITRE_BEND': ['aborted']})
    outcome = mission(robot).run()
    assert outcome.status == 'succeeded'
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'CLAMP_SIDEWAYS',
                                           'MITRE_BEND', 'DRIVE', 'HOME']
    assert any('retrying' in line for line in outcome.log)


def test_retries_run_out_and_the_mission_stops_with_nothing_more_sent():
    robot = FakeRobot(0.3, fail={'MITRE_BEND': ['aborted'] * 5})
    outcome = mission(robot, policy={'MITRE_BEND': {'retries': 2}}).run()
    assert outcome.status == 'aborted' and 'MITRE_BEND' in outcome.message
    assert [g[0] for g in robot.goals].count('MITRE_BEND') == 3
    assert robot.goals[-1][0] == 'MITRE_BEND'


@pytest.mark.parametrize('status', ['rejected'])
def test_a_refused_goal_is_not_retried(status):
    robot = FakeRobot(0.3, fail={'DRIVE': [status]})
    outcome = mission(robot).run()
    assert outcome.status == 'aborted' and [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']


def test_a_junction_pab_refused_at_its_start_is_retried_after_reclamping():
    """The drive up to a junction may roll the robot out of its clamp's
    region; the junction PAB refuses to start; the retry re-clamps first."""
    robot = FakeRobot(0.3, fail={'MITRE_BEND': ['rejected']})
    outcome = mission(robot).run()
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'CLAMP_SIDEWAYS',
                                           'MITRE_BEND', 'DRIVE', 'HOME']
    robot = FakeRobot(0.3, fail={'MITRE_BEND': ['rejected'] * 5})        # refused again: the mission ends
    outcome = mission(robot).run()                                      # after the free re-clamp and 1 retry
    assert outcome.status == 'aborted' and [g[0] for g in robot.goals].count('MITRE_BEND') == 3


def test_a_refusal_at_the_start_cured_by_a_reclamp_does_not_spend_the_steps_retry():
    """The drive up to a bend routinely rolls the robot out of its clamp's
    region (the twin: 3.05 rad for 3.14): that re-clamp must leave the one
    retry of the policy for an abort later in the turn."""
    robot = FakeRobot(0.3, fail={'MITRE_BEND': ['rejected', 'aborted']})
    outcome = mission(robot).run()
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'CLAMP_SIDEWAYS', 'MITRE_BEND',
                                           'CLAMP_SIDEWAYS', 'MITRE_BEND', 'DRIVE', 'HOME']


def test_a_cancel_from_outside_the_mission_is_not_retried():
    robot = FakeRobot(0.3, fail={'DRIVE': ['preempted']})
    outcome = mission(robot).run()
    assert outcome.status == 'cancelled' and 'outside the mission' in outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']


def test_a_step_cancelled_for_a_rogue_writer_ends_the_mission_naming_the_writer():
    robot = FakeRobot(0.3)
    rogue = 'DRIVE cancelled during drive: second writer on /pirate/control_array: /rostopic_4711'
    robot.fail = {'DRIVE': ['preempted']}
    robot.run = lambda step, run=robot.run: run(step)._replace(message=rogue) if step.pab == 'DRIVE' else run(step)
    outcome = mission(robot).run()
    assert outcome.status == 'cancelled' and '/rostopic_4711' in outcome.message, outcome.message


def _in_thread(run):
    result = {}
    thread = threading.Thread(target=lambda: result.update(outcome=run.run()), daemon=True)
    thread.start()
    return thread, result


def test_operator_cancel_during_a_step_ends_the_mission_and_is_never_retried():
    robot = FakeRobot(0.3, hold_step='DRIVE')
    run = mission(robot)
    thread, result = _in_thread(run)
    assert robot.entered.wait(WAIT_S)
    run.cancel()
    thread.join(WAIT_S)
    assert result['outcome'].status == 'cancelled'
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']


class Waiter(object):
    """Progress callback that lets a test wait for a state."""

    def __init__(self):
        self.cond, self.seen = threading.Condition(), []

    def __call__(self, progress):
        with self.cond:
            self.seen.append(progress)
            self.cond.notify_all()

    def wait_for(self, predicate):
        with self.cond:
            assert self.cond.wait_for(lambda: any(predicate(p) for p in self.seen), WAIT_S)
            self.seen.clear()


def paused_mission(robot, resumes=True, world=MAP):
    """Run a mission, pause it while ``robot.hold_step`` runs and, if the
    mission waits for it, resume: (executive, outcome)."""
    waiter = Waiter()
    run = mission(robot, progress=waiter, world=world)
    thread, result = _in_thread(run)
    assert robot.entered.wait(WAIT_S)
    run.pause()
    if resumes:
        waiter.wait_for(lambda p: p.waiting_for.startswith('resume'))
        run.resume()
    thread.join(WAIT_S)
    return run, result['outcome']


@pytest.mark.parametrize('clamped_after, reclamped', [(False, True), (True, False)])
def test_pause_holds_and_resume_reclamps_only_if_unclamped_then_drives_only_what_is_left(clamped_after,
                                                                                          reclamped):
    robot = FakeRobot(0.3, hold_step='DRIVE')
    robot.clamped_after_cancel = clamped_after
    outcome = paused_mission(robot)[1]
    assert outcome.status == 'succeeded', outcome.message
    kinds = [g[0] for g in robot.goals]
    again = ['CLAMP_SIDEWAYS'] if reclamped else []
    assert kinds == ['CLAMP_SIDEWAYS', 'DRIVE'] + again + ['DRIVE', 'MITRE_BEND', 'DRIVE', 'HOME']
    first, rest = robot.goals[1][2], robot.goals[2 + len(again)][2]
    assert first + 0 == pytest.approx(2 * rest, abs=2)   # half was driven before the pause


@pytest.mark.parametrize('moved_mm, goes_on', [(30.0, True), (200.0, False)])
def test_a_crossing_paused_after_sensing_runs_again_only_while_its_front_v_has_not_passed_it(moved_mm, goes_on):
    """Straight on through a T-joint, paused after the PAB sensed it:
    re-anchored there; within the junction's length (90 mm) the step runs
    again from where the robot is; beyond it the crossing cannot be resumed:
    the mission stops, nothing more is sent."""
    robot = FakeRobot(0.3, hold_step='T_JOINT')
    robot.sensed_then_moved_mm = moved_mm
    run, outcome = paused_mission(robot, resumes=goes_on, world=TEE_MAP)
    assert run.localiser.fixes[0].junction == 'tee_1'
    if goes_on:
        assert outcome.status == 'succeeded', outcome.message
        assert [g[0] for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT', 'CLAMP_STRAIGHT',
                                               'T_JOINT', 'DRIVE', 'HOME']
    else:
        assert outcome.status == 'aborted' and 'cannot be resumed' in outcome.message
        assert 'tee_1' in outcome.message and '200 mm after sensing' in outcome.message
        assert [g[0] for g in robot.goals] == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT']


def aborts_once_after_sensing(robot, pab, moved_mm, then=()):
    """``robot``'s first ``pab`` goal aborts ``moved_mm`` past where it sensed
    its junction; the next ones end with the statuses ``then`` (rejected:
    refused at its start), then run as usual."""
    take, later = robot.run, list(then)

    def run(step):
        if step.pab == pab and not robot.aborted:
            robot.aborted = True
            robot.true_m = sensed_at_m(step.junction, 1, SETTINGS['robot']) + moved_mm / 1000.0
            robot.goals.append((step.pab, step.option, round(step.distance_mm)))
            return ex.Report('aborted', 'no robot state', robot.odometry(), robot.odometry() - moved_mm, False)
        if step.pab == pab and later:
            robot.goals.append((step.pab, step.option, round(step.distance_mm)))
            return ex.Report(later.pop(0), 'scripted', robot.odometry(), None, False)
        return take(step)
    robot.aborted, robot.run = False, run


@pytest.mark.parametrize('moved_mm, goes_on', [(30.0, True), (200.0, False)])
def test_a_crossing_aborted_after_sensing_is_retried_only_while_its_front_v_has_not_passed_it(moved_mm, goes_on):
    """The retry policy follows the pause's rule: a crossing that aborted
    after its front V had passed the junction cannot sense it again; the
    mission stops with that reason instead of reporting a missing junction."""
    robot = FakeRobot(0.3)
    aborts_once_after_sensing(robot, 'T_JOINT', moved_mm)
    outcome = mission(robot, world=TEE_MAP).run()
    kinds = [g[0] for g in robot.goals]
    if goes_on:
        assert outcome.status == 'succeeded', outcome.message
        assert kinds == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT', 'CLAMP_STRAIGHT', 'T_JOINT', 'DRIVE', 'HOME']
    else:
        assert outcome.status == 'aborted' and 'abort in step 3' in outcome.message
        assert 'cannot be resumed' in outcome.message and kinds == ['CLAMP_STRAIGHT', 'DRIVE', 'T_JOINT']


@pytest.mark.parametrize('moved_mm', [30.0, 200.0])
def test_a_turn_paused_after_its_front_turned_is_sent_again_without_a_reclamp_and_goes_on(moved_mm):
    """Half round the corner a Clamp Sideways would undo the turn; the turn's
    PAB goes on from where the robot senses it is and, not steering again,
    senses no junction: that is not a missing junction. The mission ends at
    its target, the bend anchored once."""
    robot = FakeRobot(0.3, hold_step='MITRE_BEND')
    robot.sensed_then_moved_mm = moved_mm
    run, outcome = paused_mission(robot)
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'MITRE_BEND', 'DRIVE', 'HOME']
    assert [fix.junction for fix in run.localiser.fixes] == ['mitre_1']
    assert abs(robot.true_m - 3.0) < 1e-6 and abs(run.localiser.along_m - 3.0) < 1e-6
    assert any('sent again as it is' in line for line in outcome.log)


def test_a_turn_aborted_after_its_front_turned_is_retried_without_a_reclamp():
    robot = FakeRobot(0.3)
    aborts_once_after_sensing(robot, 'MITRE_BEND', 200.0)
    outcome = mission(robot).run()
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'MITRE_BEND', 'DRIVE', 'HOME']


def test_a_begun_turn_its_pab_refuses_to_go_on_with_is_re_clamped_and_sent_again():
    """The PAB refuses what it cannot continue from (e.g. "Clamp Sideways
    LEFT first"): the retry's re-clamp follows, as for any junction PAB."""
    robot = FakeRobot(0.3)
    aborts_once_after_sensing(robot, 'MITRE_BEND', 200.0, then=['rejected'])
    outcome = mission(robot, policy={'MITRE_BEND': {'retries': 2}}).run()
    assert outcome.status == 'succeeded', outcome.message
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE', 'MITRE_BEND', 'MITRE_BEND', 'CLAMP_SIDEWAYS',
                                           'MITRE_BEND', 'DRIVE', 'HOME']


def test_confirm_level_waits_for_the_operator_before_each_pab():
    robot, waiter = FakeRobot(0.3), Waiter()
    run = mission(robot, progress=waiter, level=ex.CONFIRM)
    thread, result = _in_thread(run)
    for number in range(1, 6):
        waiter.wait_for(lambda p, n=number: p.waiting_for.startswith('confirmation of step %d' % n))
        assert len(robot.goals) == number - 1      # nothing ran before the confirmation
        run.confirm()
    thread.join(WAIT_S)
    assert result['outcome'].status == 'succeeded' and len(robot.goals) == 5


def test_manual_level_only_shows_the_plan():
    robot = FakeRobot(0.3)
    outcome = mission(robot, level=ex.MANUAL).run()
    assert outcome.status == 'manual' and robot.goals == []


def test_a_junction_far_from_where_the_map_has_it_stops_the_mission():
    robot = FakeRobot(0.3, shift_mm=-380)       # found 380 mm early, within the 400 mm search
    outcome = mission(robot).run()
    assert outcome.status == 'mismatch' and 'mitre_1 found' in outcome.message
    assert robot.goals[-1][0] == 'MITRE_BEND'


def test_a_junction_not_found_where_the_map_has_one_stops_the_mission():
    robot = FakeRobot(0.3, shift_mm=900)
    outcome = mission(robot).run()
    assert outcome.status == 'mismatch' and 'mitre_1 not found' in outcome.message
    assert [g[0] for g in robot.goals].count('MITRE_BEND') == 1


def test_a_junction_further_on_than_the_map_says_is_searched_for_only_as_far_as_the_map_allows():
    """The pipe's bend 300 mm further on than the map has it: the junction PAB
    is sent to search from the estimate to the map's bend plus the
    localiser's uncertainty there (less than the plan's search), reports the
    junction missing at that bound, and the mission stops: no step after it
    (no turn, no retry), and the reason names where the map has the bend,
    from where to where along the map it was looked for and how far the
    estimate may be off there."""
    robot = FakeRobot(0.3, shift_mm=300)
    outcome = mission(robot).run()
    # from the planned stop (2000 - 315 - 100 mm) the bend is sensed with the middle at its
    # entry (sense_turn_mm 0); 1285 mm from the anchor, d - 415 = 150 + 0.05 (1285 + d)
    bound_mm = (415.0 + 150.0 + 0.05 * 1285.0) / 0.95
    assert round(bound_mm) == 662 < SETTINGS['search_mm']
    assert robot.goals == [('CLAMP_SIDEWAYS', 'LEFT', 0), ('DRIVE', None, 1285), ('MITRE_BEND', 'LEFT', 662)]
    assert outcome.status == 'mismatch', outcome.message
    assert ('mitre_1 not found within 662 mm: the map has it at 2000 mm (the robot\'s middle at 2000 mm when it '
            'senses it); searched from 1585 to 2247 mm along the map, the estimate within 247 mm there'
            in outcome.message), outcome.message
    assert outcome.message in outcome.log[-1]


def test_an_estimate_already_beyond_the_reach_of_the_maps_junction_sends_no_junction_pab():
    robot = FakeRobot(0.3)
    drive = robot.run

    def overshooting(step):
        report = drive(step)
        if step.pab == 'DRIVE':
            robot.start_m -= 0.8                       # counted 800 mm more than planned
            report = report._replace(odometry_mm=robot.odometry())
        return report
    robot.run = overshooting
    outcome = mission(robot).run()
    assert [g[0] for g in robot.goals] == ['CLAMP_SIDEWAYS', 'DRIVE']
    assert outcome.status == 'mismatch' and 'mitre_1 not found within 0 mm' in outcome.message, outcome.message


@pytest.mark.parametrize('start_m, moved_mm, sign, junction_mm', [
    (0.3, 200.0, 1, 2000.0), (3.0, -200.0, -1, 2000.0),      # on from the anchor, forward and back
    (1.2, -200.0, 1, 1500.0), (2.0, -1000.0, 1, 1200.0)])    # back behind it, then forward: both sides
def test_the_search_ends_where_a_junction_sensed_would_no_longer_be_the_maps(start_m, moved_mm, sign, junction_mm):
    """A junction sensed at the search's far end (within 0.01 mm) is taken for the map's; 1 mm
    further on it is a mismatch; the estimate on from the anchor or behind it."""
    tee_map = network.build({'name': 'tee', 'diameter_mm': 90, 'pieces': [
        {'type': 'straight', 'length_mm': junction_mm}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
        {'type': 'straight', 'length_mm': 2000}]})
    (tee,) = planner.junctions(tee_map)
    for beyond_mm, taken in ((-0.01, True), (1.0, False)):
        localiser = Localiser(start_m, SETTINGS)
        localiser.update(0.0)
        localiser.update(moved_mm)
        search = localiser.search(tee, sign, 5000.0)
        assert search.from_m == pytest.approx(start_m + moved_mm / 1000.0) and sign * (search.to_m - search.from_m) > 0
        odometry_mm = (search.to_m - start_m) * 1000.0 + sign * beyond_mm
        if taken:
            localiser.junction_found(tee, odometry_mm, sign)
        else:
            with pytest.raises(MapMismatch):
                localiser.junction_found(tee, odometry_mm, sign)


def _back_from(start_m, fixes=()):
    """A localiser at ``start_m``, its odometry 0 there, with ``fixes``."""
    localiser = Localiser(start_m, SETTINGS)
    localiser.update(0.0)
    localiser.fixes.extend(fixes)
    return localiser


def test_a_turn_taken_back_through_a_junction_found_on_the_way_in_allows_its_steerings_slip():
    """Back through a bend found on the way in, a rear-first turn's search
    reaches further: ``steer_slip`` of its odometry may be slip (the rear
    pushing the far wall), and a bend sensed at its far end is the map's,
    1 mm beyond it not. The same bend not found before is searched for and
    checked strictly, and a bend sensed short of the map gets no slip."""
    (mitre,) = planner.junctions(MAP)
    found = [Fix(mitre.name, mitre.exit_m, mitre.exit_m)]
    expected_m = sensed_at_m(mitre, -1, SETTINGS['robot'])
    reach_mm = {}
    for fixes in ((), found):
        search = _back_from(3.0, fixes).search(mitre, -1, 5000.0)
        reach_mm[bool(fixes)] = (3.0 - search.to_m) * 1000.0
        for beyond_mm, taken in ((-0.01, True), (1.0, False)):
            localiser = _back_from(3.0, fixes)
            localiser.search(mitre, -1, 5000.0)
            if taken:
                assert localiser.junction_found(mitre, -reach_mm[bool(fixes)] - beyond_mm, -1) == expected_m
            else:
                with pytest.raises(MapMismatch):
                    localiser.junction_found(mitre, -reach_mm[bool(fixes)] - beyond_mm, -1)
    # 910 mm from the bend's exit: 150 + 0.05 d + 0.4 d = d - 910 (found), 150 + 0.05 d = d - 910 (not)
    assert reach_mm[False] == pytest.approx(1060.0 / 0.95) and reach_mm[True] == pytest.approx(1060.0 / 0.55)
    short = _back_from(3.0, found)
    short.search(mitre, -1, 5000.0)
    with pytest.raises(MapMismatch):      # sensed 190 mm short of the map, 720 mm on: 150 + 0.05 * 720 < 190
        short.junction_found(mitre, (expected_m - 3.0) * 1000.0 + 190.0, -1)


def test_the_search_is_no_longer_than_the_plans():
    (mitre,) = planner.junctions(MAP)
    localiser = Localiser(0.3, SETTINGS)
    search = localiser.search(mitre, 1, 250.0)
    assert search.to_m == pytest.approx(0.55) and search.from_m == pytest.approx(0.3)


def test_the_way_back_reanchors_at_the_junction_rear_first():
    robot = FakeRobot(0.3, shift_mm=40)
    run = mission(robot, route=('pit', 'target', 'pit'))
    outcome = run.run()
    assert outcome.status == 'succeeded', outcome.message
    assert len(run.localiser.fixes) == 2 and abs(run.localiser.along_m - 0.3) < 1e-6
    # the true first straight is 40 mm longer than mapped: unobservable after the
    # last junction, so the robot stops where the map's pit would be from there
    assert abs(robot.true_m - 0.34) < 1e-6


def test_a_turn_anchors_the_middle_at_the_bend_straight_on_through_a_tee_before_it():
    """The two ways a junction PAB senses its junction put the middle at
    different places (config/supervisory.yaml sense_turn_mm / sense_front_mm)."""
    tee_map = network.build({'name': 'tee', 'diameter_mm': 90, 'pieces': [
        {'type': 'straight', 'length_mm': 1000}, {'type': 'tee', 'enter': 'run', 'side': 'up'},
        {'type': 'straight', 'length_mm': 1000}]})
    (mitre,), (tee,) = planner.junctions(MAP), planner.junctions(tee_map)
    robot = dict(SETTINGS['robot'], sense_front_mm=100.0, sense_rear_mm=70.0, sense_turn_mm=20.0)
    assert sensed_at_m(mitre, 1, robot) == pytest.approx(mitre.entry_m - 0.020)
    assert sensed_at_m(tee, 1, robot) == pytest.approx(tee.entry_m - 0.100)
    # rear first: a turn round the corner at the exit as front first at the entry; straight on, the rear V's apex
    assert sensed_at_m(mitre, -1, robot) == pytest.approx(mitre.exit_m + 0.020)
    assert sensed_at_m(tee, -1, robot) == pytest.approx(tee.exit_m + 0.070)


def test_progress_counts_steps_and_time_left_goes_down():
    robot, waiter = FakeRobot(0.3), Waiter()
    mission(robot, progress=waiter).run()
    # every step was announced, in order, and the estimate of time left never grew
    steps = [p.step for p in waiter.seen]
    assert steps == sorted(steps) and steps[-1] == 5
    lefts = [p.time_left_s for p in waiter.seen]
    assert all(a >= b for a, b in zip(lefts, lefts[1:]))


def test_a_bad_level_is_refused():
    with pytest.raises(ValueError, match='autonomy level'):
        mission(FakeRobot(0.3), level='auto')


@pytest.mark.parametrize('text, ok, level', [
    ('level confirm', True, ex.CONFIRM), ('LEVEL manual', True, ex.MANUAL), ('level auto', False, ex.FULL),
    ('jump', False, ex.FULL), ('', False, ex.FULL)])
def test_operator_words_change_the_level_or_are_refused_with_the_reason(text, ok, level):
    run = mission(FakeRobot(0.3))
    answer = run.command(text)
    assert answer[0] is ok and run.level == level
    assert ok or ('unknown command' in answer[1] or 'autonomy level' in answer[1])


def test_pause_word_before_the_first_step_holds_the_mission_until_resume():
    robot, waiter = FakeRobot(0.3), Waiter()
    run = mission(robot, progress=waiter)
    assert run.command('pause')[0]
    thread, result = _in_thread(run)
    waiter.wait_for(lambda p: p.waiting_for.startswith('resume'))
    assert robot.goals == []
    assert run.command('resume')[0]
    thread.join(WAIT_S)
    assert result['outcome'].status == 'succeeded'


@pytest.mark.parametrize('text, ok, level', [
    ('level confirm', True, ex.CONFIRM), ('level auto', False, ex.FULL), ('pause', False, ex.FULL),
    ('confirm', False, ex.FULL)])
def test_between_missions_only_the_next_missions_level_can_be_set(text, ok, level):
    answer = ex.between_missions(text, ex.FULL)
    assert answer[0] is ok and answer[2] == level
    assert ok or answer[1] == 'no mission is running'


def test_the_localisers_uncertainty_is_its_tolerance_plus_the_drift_since_the_anchor():
    localiser = Localiser(0.4, SETTINGS)
    tolerance_m = SETTINGS['locate_tolerance_mm'] / 1000.0
    assert localiser.uncertainty_m(7000.0) == pytest.approx(tolerance_m)       # before any reading
    localiser.update(7000.0)
    assert localiser.uncertainty_m(5000.0) == pytest.approx(tolerance_m + SETTINGS['odometry_drift'] * 2.0)
    localiser.turn_taken(1.7, 9000.0)
    assert localiser.uncertainty_m(9000.0) == pytest.approx(tolerance_m)
