"""What the diagnostics say (pirate.health), without ROS."""
import math

from pirate import health


class Stat(object):
    """The part of diagnostic_updater's DiagnosticStatusWrapper that fill uses."""

    def __init__(self):
        self.level, self.message, self.values = None, None, {}

    def summary(self, level, message):
        self.level, self.message = level, message

    def add(self, key, value):
        self.values[key] = value


def test_robot_state_freshness():
    assert health.robot_state(0.05, 0.3).level == health.OK
    stale = health.robot_state(0.5, 0.3)
    assert stale.level == health.ERROR and 'refused' in stale.message
    assert health.robot_state(math.inf, 0.3).level == health.ERROR


def test_server_reports_its_state_and_running_primitive():
    idle = health.server('Idle Clamped', None, '', False, 90)
    assert idle.level == health.OK and idle.message == 'Idle Clamped'
    running = health.server('Clamp Straight', 'CLAMP_STRAIGHT', 'clamp rear', False, 110)
    assert 'clamp rear' in running.message and ('pipe_diameter_mm', 110) in running.values
    assert health.server('Idle (no robot state)', None, '', False, 90).level == health.WARN


def test_panel_device_and_fill():
    stat = health.fill(Stat(), health.panel_device(False, 'nanoKONTROL2', ''))
    assert stat.level == health.ERROR and 'not connected' in stat.message
    assert stat.values['device asked'] == 'nanoKONTROL2'
    assert health.panel_device(True, '', 'nanoKONTROL2 MIDI 1').level == health.OK


def test_command_writers_name_the_rogue_as_an_error_and_are_ok_alone():
    alone = health.command_writers([], '/pirate_manager')
    assert alone.level == health.OK and '/pirate_manager' in alone.message
    rogue = health.command_writers([('/pirate/setpoint_array', '/rostopic_1')], '/pirate_manager')
    assert rogue.level == health.ERROR
    assert '/rostopic_1 on /pirate/setpoint_array' in rogue.message
    assert ('/pirate/setpoint_array', '/rostopic_1') in rogue.values


def test_small_states_name_the_silent_boards():
    assert health.small_states(False, '', 0.05, 9).level == health.OK
    assert health.small_states(False, '', float('inf'), 9).level == health.ERROR
    stale = health.small_states(True, 'board 22 silent', 0.4, 9)
    assert stale.level == health.ERROR and 'board 22 silent' in stale.message


def test_small_states_show_each_boards_loss_rate():
    lossy = health.small_states(False, '', 0.05, 9, {22: 0.1, 21: 0.0})
    assert lossy.level == health.OK
    assert ('board 22 loss', '10.0 %') in lossy.values and ('board 21 loss', '0.0 %') in lossy.values


def test_panel_goals_warn_until_the_panel_reaches_the_server():
    assert health.panel_goals(False).level == health.WARN
    assert 'refused' in health.panel_goals(False).message
    assert health.panel_goals(True) == health.Report(health.OK, 'connected to the Pirate Server', [('connected', True)])
    assert health.panel_goals(None).level == health.OK and 'no panel' in health.panel_goals(None).message
