"""An inspection job's file and which marks fall due as the estimate moves (pirate.inspection.job)."""
import pytest

from pirate.inspection import job as jobs
from pirate.inspection.job_node import DEFAULT_JOB
from pirate.supervisory import planner
from pirate.supervisory.plan_cli import load_settings
from pirate.world import network

GOOD = 'map: inspection_network_90\nroute: [launch_pit, past_tee, launch_pit]\nmarks:\n'


def _load(tmp_path, text):
    path = tmp_path / 'job.yaml'
    path.write_text(text)
    return jobs.load(str(path))


def test_the_demo_job_plans_there_and_back_and_marks_within_the_route():
    job = jobs.load(DEFAULT_JOB)
    settings, max_drive_mm = load_settings()
    pipe_map = network.load(network.world_path(job.map))
    plan = planner.plan(pipe_map, job.points, settings, max_drive_mm, None, True)
    planner.check_runnable(plan)
    farthest_mm = max(pipe_map.points[p] for p in job.points) * 1000
    nearest_mm = min(pipe_map.points[p] for p in job.points) * 1000
    assert job.marks and all(nearest_mm < m.along_mm < farthest_mm for m in job.marks), job.marks
    assert {m.leg for m in job.marks} == {'in', 'back'}
    assert job.stops and all(nearest_mm < s.along_mm < farthest_mm for s in job.stops), job.stops


def test_a_stop_looks_the_ways_its_job_says_or_round_the_wall(tmp_path):
    stops = 'stops:\n  - {along_mm: 5, note: here, views_deg: [[-90, 10]]}\n  - {along_mm: 9, leg: back}\n'
    job = _load(tmp_path, GOOD + stops)
    view = (pytest.approx(-1.5708, abs=1e-4), pytest.approx(0.1745, abs=1e-4))
    assert job.stops[0] == jobs.Stop(5.0, 'in', 'here', (view,))
    assert len(job.stops[1].views) == len(jobs.DEFAULT_VIEWS_DEG) and job.stops[1].leg == 'back'


class FakeRobot(object):
    """The stack as a stop sees it: records the calls; ``refuse`` names a call that fails."""

    def __init__(self, refuse=(), stands=True, gets_there=True):
        self.calls, self._refuse, self._stands, self._there = [], refuse, stands, gets_there

    def _answer(self, name, *args):
        self.calls.append((name,) + args)
        return name not in self._refuse, '%s %s' % (name, 'refused' if name in self._refuse else 'done')

    def pause(self):
        return self._answer('pause')

    def resume(self):
        return self._answer('resume')

    def point(self, pan, tilt):
        return self._answer('point', round(pan, 3), round(tilt, 3))

    def mark(self, note):
        return self._answer('mark', note)

    def stands(self):
        self.calls.append(('stands',))
        return self._stands

    def pointed(self, pan, tilt):
        return self._there


STOP = jobs.Stop(1900.0, 'in', 'by the water', ((0.0, 0.0), (-1.0, 0.0)))


def test_a_stop_pauses_looks_each_way_marks_each_view_and_resumes():
    robot, said = FakeRobot(), []
    assert jobs.run_stop(STOP, robot, said.append) == 2
    assert [c[0] for c in robot.calls] == ['pause', 'stands', 'point', 'mark', 'point', 'mark', 'point', 'resume']
    assert robot.calls[4] == ('point', -1.0, 0.0) and robot.calls[6] == ('point', 0.0, 0.0)
    assert robot.calls[5] == ('mark', 'by the water (pan -57 deg, tilt +0 deg)')
    assert said[-1] == 'stop at 1900 mm: 2 of 2 views; resume done'


@pytest.mark.parametrize('robot, calls, marked, said', [
    (FakeRobot(refuse=('pause',)), ['pause'], 0, 'stop at 1900 mm not made: pause refused'),
    (FakeRobot(stands=False), ['pause', 'stands', 'resume'], 0, 'did not come to rest; no views'),
    (FakeRobot(refuse=('point',)), ['pause', 'stands', 'point', 'resume'], 0, 'point refused'),
    (FakeRobot(gets_there=False), ['pause', 'stands'] + ['point', 'mark'] * 2 + ['point', 'resume'], 2,
     'the camera had not got there'),
])
def test_a_stop_that_cannot_look_says_why_and_the_mission_goes_on(robot, calls, marked, said):
    lines = []
    assert jobs.run_stop(STOP, robot, lines.append) == marked
    assert [c[0] for c in robot.calls] == calls
    assert any(said in line for line in lines) or any(said in str(c) for c in robot.calls), (lines, robot.calls)


@pytest.mark.parametrize('text, said', [
    ('route: [a, b]\n', 'names its map'),
    ('map: m\nroute: [a]\n', 'two points or more'),
    (GOOD + '  - {along_mm: -5, kind: leak}\n', 'along_mm must be a distance'),
    (GOOD + '  - {along_mm: true, kind: leak}\n', 'along_mm must be a distance'),
    (GOOD + '  - {along_mm: 5, leg: sideways}\n', 'leg must be one of in, back'),
    (GOOD + '  - {along_mm: 5, kind: gold}\n', "kind 'gold' is not one of"),
    (GOOD + '  - {along_mm: 5, knd: leak}\n', 'unknown key(s) knd'),
    (GOOD + '  - 5\n', 'mark 1: {along_mm, leg, kind, note}'),
    ('map: [\n', 'job.yaml'),
    (GOOD + 'stop:\n', 'unknown key(s) stop (map, route, marks, stops)'),
    (GOOD + 'stops:\n  - {along_mm: -1}\n', 'stops, entry 1: along_mm must be a distance'),
    (GOOD + 'stops:\n  - {along_mm: 5, views_deg: []}\n', 'stops, entry 1: views_deg must be [pan, tilt] pairs'),
    (GOOD + 'stops:\n  - {along_mm: 5, views_deg: [[0]]}\n', 'views_deg must be [pan, tilt] pairs'),
    (GOOD + 'stops:\n  - {along_mm: 5, views_deg: [[200, 0]]}\n', 'in degrees within +-180'),
    (GOOD + 'stops:\n  - {along_mm: 5, views_deg: [[true, 0]]}\n', 'views_deg must be'),
    (GOOD + 'stops:\n  - {along_mm: 5, kind: leak}\n', 'unknown key(s) kind (along_mm, leg, note, views_deg)'),
])
def test_a_bad_job_file_is_refused_naming_what_is_wrong(tmp_path, text, said):
    with pytest.raises(jobs.JobError) as refused:
        _load(tmp_path, text)
    assert said in str(refused.value)


def _marks(*rows):
    return [jobs.Mark(along, leg, kind, '') for along, leg, kind in rows]


def test_marks_fall_due_once_as_the_estimate_passes_them_on_their_leg():
    marks = _marks((800, 'in', 'leak'), (2190, 'in', 'water'), (2190, 'back', 'water'), (5000, 'in', 'crack'))
    due = jobs.DueMarks(marks)
    # (signed distance of the running step, estimate): in, a re-anchoring jump back
    # at the T-joint, on to the far point, then back rear first
    path = [(0, 400), (500, 790), (500, 830), (700, 2100), (700, 2000), (700, 2200), (700, 2250), (900, 3200),
            (-900, 3150), (-900, 3050), (-700, 2300), (-700, 2150), (-700, 2250), (-700, 800), (0, 400)]
    seen = []
    for distance, along in path:
        due.step(distance)
        seen.append((along, [m.kind + '/' + m.leg for m in due.passed(along)]))
    assert [s for s in seen if s[1]] == [(830, ['leak/in']), (2200, ['water/in']), (2150, ['water/back'])]
    assert [m.kind for m in due.left()] == ['crack']


def test_marks_passed_in_one_step_come_in_the_order_passed():
    due = jobs.DueMarks(_marks((900, 'in', 'leak'), (850, 'in', 'crack')))
    due.passed(800)
    assert [m.kind for m in due.passed(1000)] == ['crack', 'leak']


#: The inspection network's first bend (mm along the map) and the robot's reach (middle to its wheels).
BEND_MM, REACH_MM = (1200.0, 1200.0), 315.0


def test_no_mark_falls_due_while_a_junction_pab_takes_a_corner_but_after_it():
    """Round a corner the estimate is odometry that runs ahead of the robot's
    middle: a mark passed then fell due about 260 mm early (the round trip's
    1790 mm mark, every run)."""
    due = jobs.DueMarks(_marks((1790, 'in', 'corrosion'), (1300, 'in', 'leak')), [BEND_MM], REACH_MM)
    path = [(1, 'DRIVE', 382, 785), (2, 'MITRE_BEND', 700, 1500), (2, 'MITRE_BEND', 700, 1950),  # ahead round
            (3, 'CLAMP_STRAIGHT', 0, 1690), (4, 'DRIVE', 386, 1750), (4, 'DRIVE', 386, 1800)]  # re-anchored
    seen = []
    for number, pab, distance, along in path:
        due.step(distance, pab, number)
        seen.append((pab, along, [m.kind for m in due.passed(along)]))
    assert [s for s in seen if s[2]] == [('CLAMP_STRAIGHT', 1690, ['leak']), ('DRIVE', 1800, ['corrosion'])]


def test_a_mark_passed_before_the_corner_falls_due_during_the_junction_pab():
    """The route's first PAB takes the bend from the launch pit: the leak at
    800 mm, passed with the leading wheel still 85 mm short of the bend,
    fell due only once the turn had ended, at 1290 mm."""
    due = jobs.DueMarks(_marks((800, 'in', 'leak'), (1000, 'in', 'crack')), [BEND_MM], REACH_MM)
    due.step(700, 'MITRE_BEND', 1)
    assert [m.kind for m in due.passed(400)] == []
    assert [m.kind for m in due.passed(810)] == ['leak']
    assert [m.kind for m in due.passed(1010)] == []        # the wheel at the bend: held
    due.step(0, 'CLAMP_STRAIGHT', 2)
    assert [m.kind for m in due.passed(1290)] == ['crack']


def test_a_t_joint_crossed_straight_on_holds_no_mark():
    corners = jobs.corners_mm(network.load(network.world_path('inspection_network_90')))
    assert len(corners) == 2        # the two bends; the T-joint is crossed straight on
    due = jobs.DueMarks(_marks((2190, 'in', 'water')), corners, REACH_MM)
    due.step(700, 'T_JOINT', 3)
    assert [m.kind for m in due.passed(2100)] == []
    assert [m.kind for m in due.passed(2200)] == ['water']
