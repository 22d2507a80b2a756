"""The virtual panel's status lines tell the truth (pirate.panel.status), table-driven:
each scenario is the news in order and the lines the operator reads after it."""
import os

import pytest

from pirate import paths
from pirate.panel import config, status

PARTLY = 'Idle Partly Clamped (front partly, rear partly)'

# (news in order, PAB line after, mission line after)
SCENARIOS = {
    'a late feedback does not overwrite the result': (
        [('feedback', 'g1', 'PAB running: Clamp Sideways / clamping front'),
         ('result', 'g1', 'PAB aborted: robot state stale'),
         ('feedback', 'g1', 'Server: Idle Clamped ')],
        'PAB aborted: robot state stale', ''),
    'after the outcome the server says its state': (
        [('result', 'g1', 'PAB aborted: robot state stale'), ('server', False, PARTLY)],
        'PAB aborted: robot state stale | Server: ' + PARTLY, ''),
    'while idle the state follows the server': (
        [('result', 'g1', 'PAB succeeded: clamped'), ('server', False, 'Idle Clamped'), ('server', False, PARTLY)],
        'PAB succeeded: clamped | Server: ' + PARTLY, ''),
    'a running goal shows its feedback alone': (
        [('server', True, 'Clamp Straight'), ('feedback', 'g2', 'PAB running: Clamp Straight / clamping rear')],
        'PAB running: Clamp Straight / clamping rear', ''),
    'a manager that does not answer says so': (
        [('result', 'g1', 'PAB succeeded: clamped'), ('server', False, None)],
        'PAB succeeded: clamped | Server: ' + status.NO_ANSWER, ''),
    'nothing stale after a manager restart': (
        [('mission', 'succeeded: 5 steps'), ('result', 'g1', 'PAB succeeded: homed'), ('server', False, 'Idle'),
         ('server', False, None), ('server', False, 'Idle Unclamped')],
        status.NO_NEWS + ' | Server: Idle Unclamped', ''),
    'the next goal after a result runs': (
        [('result', 'g1', 'PAB aborted: x'), ('feedback', 'g2', 'PAB running: Drive / driving')],
        'PAB running: Drive / driving', ''),
}


def _apply(panel_status, news):
    kind, args = news[0], news[1:]
    if kind == 'feedback':
        panel_status.feedback(*args)
    elif kind == 'result':
        panel_status.result(*args)
    elif kind == 'server':
        panel_status.server_status(*args)
    else:
        panel_status.mission_line(*args)


@pytest.mark.parametrize('name', sorted(SCENARIOS))
def test_the_status_lines_tell_the_truth(name):
    news, pab_line, mission_line = SCENARIOS[name]
    panel_status = status.PanelStatus()
    for item in news:
        _apply(panel_status, item)
    assert panel_status.pab_line() == pab_line
    assert panel_status.mission == mission_line


def _fits(width):
    return lambda text: len(text) <= width


@pytest.mark.parametrize('text,width,lines', [
    ('WAITING for confirmation of step 5 (MITRE_BEND)', 20,
     ['WAITING for', 'confirmation of step', '5 (MITRE_BEND)']),
    ('short', 20, ['short']),
    ('', 20, ['']),
    ('abcdefghij', 4, ['abcd', 'efgh', 'ij']),
])
def test_lines_are_wrapped_not_clipped(text, width, lines):
    assert status.wrap(text, _fits(width)) == lines
    assert ' '.join(status.wrap(text, _fits(width))).replace(' ', '') == text.replace(' ', '')


def test_manual_labels_come_from_the_panel_map():
    labels = status.control_labels(config.load(os.path.join(paths.CONFIG_DIR, 'nanokontrol2.yaml')))
    assert labels[1] == 'Bend IV' and labels[7] == 'wheels' and labels[17] == 'limit Bend IV'
    assert labels[5] == 'front module' and labels[23] == 'rotational module'
    assert 0 not in labels          # slider 1 moves nothing


def test_robot_line_shows_joints_odometry_along_and_leds():
    line = status.robot_line({'front_tilt': 0.38, 'bend_i': -0.8, 'rotation': 0.0}, 412.4, 1885.0,
                             {'front': 120, 'rear': 0})
    assert line == ('Robot: joints (rad) front +0.38 I -0.80 rot +0.00 | odometry 412 mm, along the pipe 1885 mm'
                    ' | LEDs front on (120), rear off')
    assert 'along the pipe: no mission' in status.robot_line({}, 0.0)


# (typical s of the sent goal, robot time it was sent, goal id of the feedback, now: the PAB line's end)
TIME_LEFT = {
    'half way': (25.0, 100.0, 'g3', 112.0, ' | about 13 s left (typically 25 s)'),
    'over its typical time': (25.0, 100.0, 'g3', 131.0, ' | 31 s so far, longer than the typical 25 s'),
    'a feedback of another goal': (25.0, 100.0, 'g4', 112.0, ''),
    'a PAB of no typical duration': (0.0, 100.0, 'g3', 112.0, ''),
}


@pytest.mark.parametrize('name', sorted(TIME_LEFT))
def test_a_running_pab_says_its_time_left(name):
    typical, sent, running, now, end = TIME_LEFT[name]
    panel_status = status.PanelStatus()
    panel_status.goal('g3', typical, sent)
    panel_status.feedback(running, 'PAB running: Drive / driving')
    assert panel_status.pab_line(now) == 'PAB running: Drive / driving' + end


def test_an_ended_pab_says_no_time_left():
    panel_status = status.PanelStatus()
    panel_status.goal('g3', 25.0, 100.0)
    panel_status.feedback('g3', 'PAB running: Drive / driving')
    panel_status.result('g3', 'PAB succeeded: driven')
    assert 'left' not in panel_status.pab_line(112.0)
