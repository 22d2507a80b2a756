"""Unit tests of the Mapper (no ROS): edge detection, scaling, mode rules,
setpoint coherence, bad input. Real Setpoint/Control/Limit objects with
recording publishers, so the safety limits apply as on the robot."""
import os

import pytest

from pirate.robot import commands, safety, tables, units
from pirate.panel.mapper import Mapper
from pirate.panel import config as panel_config

CONFIG = os.path.join(os.path.dirname(__file__), '..', '..', 'config', 'nanokontrol2.yaml')
PRESS, RELEASE = 127, 0
PLAY, STOP, REWIND, RECORD, SET, TRACK_NEXT = 41, 42, 43, 45, 60, 59
SLIDER_BEND_I, SLIDER_CAMERA_TILT, SLIDER_DRIVE = 4, 6, 7
S_BEND_I, S_CAMERA_TILT, M_BEND_I, R_BEND_I = 36, 38, 52, 68


class Recorder(object):
    def __init__(self):
        self.messages = []

    def publish(self, msg):
        self.messages.append(msg)


class FakePab(object):
    """The pab_client contract: send_goal / cancel / is_active."""

    def __init__(self, accept=True):
        self.goals, self.cancels, self.active, self.accept = [], 0, False, accept

    def send_goal(self, goal):
        self.goals.append(tuple(goal))
        self.active = self.accept
        return self.accept, '' if self.accept else 'server busy'

    def cancel(self):
        self.cancels += 1
        self.active = False

    def is_active(self):
        return self.active


class Clock(object):
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


class Rig(object):
    def __init__(self):
        self.control_pub, self.setpoint_pub, self.limit_pub = Recorder(), Recorder(), Recorder()
        self.control = commands.Control(self.control_pub, list)
        self.setpoint = commands.Setpoint(self.setpoint_pub, list, self.control)
        self.limit = commands.Limit(self.limit_pub, list)
        self.pab = FakePab()
        self.leds, self.logs = {}, []
        self.clock = Clock()
        self.mapper = Mapper(panel_config.load(CONFIG), self.setpoint, self.control, self.limit,
                             self.pab, self.leds.__setitem__, self.logs.append, self.clock)

    def press(self, channel):
        self.mapper.handle(channel, PRESS)
        self.mapper.handle(channel, RELEASE)

    def play(self):
        self.press(PLAY)


@pytest.fixture
def rig():
    return Rig()


def test_nothing_moves_before_play(rig):
    rig.mapper.handle(SLIDER_BEND_I, 127)
    assert rig.setpoint.get('bend_i') == 0
    assert not rig.setpoint.enabled and rig.setpoint.tick() is None
    assert any('press Play' in line for line in rig.logs)


def test_play_enables_publishing_and_sends_play(rig):
    rig.play()
    assert rig.setpoint.enabled and rig.limit.enabled
    assert rig.control.get(tables.element('rear_module').index) == safety.COMMAND_CODES['play']
    assert rig.leds[PLAY] is True and rig.leds[STOP] is False


@pytest.mark.parametrize('value,expected', [(127, 256), (63, 0), (0, -252), (100, 148)])
def test_bend_i_slider_scaling_pwm(rig, value, expected):
    rig.play()
    rig.mapper.handle(SLIDER_BEND_I, value)
    assert rig.setpoint.get('bend_i') == expected   # -4 * (63 - value)


def test_bend_iii_has_the_opposite_sign(rig):
    rig.play()
    rig.mapper.handle(2, 127)
    assert rig.setpoint.get('bend_iii') == 4 * (63 - 127)


def test_camera_tilt_scale_follows_control_mode(rig):
    rig.play()
    rig.mapper.handle(SLIDER_CAMERA_TILT, 0)
    assert rig.setpoint.get('camera_tilt') == 4 * 63
    rig.press(S_CAMERA_TILT)
    assert rig.control.mode_of('camera_tilt') == 'position' and rig.leds[S_CAMERA_TILT] is True
    rig.mapper.handle(SLIDER_CAMERA_TILT, 0)
    assert rig.setpoint.get('camera_tilt') == 7 * 63


def test_wheel_velocity_is_limited_by_safety_not_mapper(rig):
    rig.play()
    rig.press(39)
    assert rig.control.mode_of('wheels') == 'velocity'
    rig.mapper.handle(SLIDER_DRIVE, 127)
    top = units.mm_s_to_wheel_counts(safety.DRIVE_MAX_MM_S)
    assert rig.setpoint.get('wheels') == top   # -1 * (63 - 127) = 64, clamped
    assert rig.control.published  # the mode change went out at once


def test_rotation_starts_in_position_mode_and_scales_by_64(rig):
    assert rig.control.mode_of('rotation') == 'position'
    rig.play()
    rig.mapper.handle(23, 60)
    assert rig.setpoint.get('rotation') == 64 * 3


def test_torque_limit_knob_and_no_limit_at_127(rig):
    rig.mapper.handle(20, 50)
    assert rig.limit.get('bend_i') == 100
    rig.mapper.handle(20, 127)
    assert rig.limit.get('bend_i') == safety.NO_LIMIT


def test_leds_minus_two_value(rig):
    rig.play()
    rig.mapper.handle(22, 100)
    rig.mapper.handle(16, 10)
    assert rig.setpoint.get('front_led') == -200 and rig.setpoint.get('rear_led') == -20


def test_button_acts_on_press_edge_only(rig):
    rig.play()
    sent = len(rig.control_pub.messages)
    for _ in range(5):
        rig.mapper.handle(S_BEND_I, PRESS)   # repeats of the same press
    assert rig.control.mode_of('bend_i') == 'torque'
    assert len(rig.control_pub.messages) == sent + 1
    rig.mapper.handle(S_BEND_I, RELEASE)
    rig.mapper.handle(S_BEND_I, PRESS)
    assert rig.control.mode_of('bend_i') == 'pwm' and rig.leds[S_BEND_I] is False


def test_m_button_sends_single_stop_at_the_joint_index(rig):
    rig.play()
    rig.press(M_BEND_I)
    assert rig.control.get(tables.element('bend_i').index) == safety.COMMAND_CODES['single_stop']


def test_stop_puts_the_robot_in_the_safe_hold(rig):
    rig.play()
    rig.press(S_BEND_I)                       # bend I in torque mode
    rig.mapper.handle(SLIDER_BEND_I, 127)     # clamping torque
    rig.mapper.handle(3, 0)                   # bend II PWM
    rig.press(S_CAMERA_TILT)
    rig.mapper.handle(SLIDER_CAMERA_TILT, 20) # camera position
    sent = len(rig.setpoint_pub.messages)
    rig.press(STOP)
    assert rig.control.get(tables.element('rear_module').index) == safety.COMMAND_CODES['stop']
    assert len(rig.setpoint_pub.messages) == sent + 1   # sent at once, not at the next tick
    last = rig.setpoint_pub.messages[-1]
    assert last[tables.element('bend_ii').index] == 0
    assert last[tables.element('bend_i').index] == 0    # zeroed before its mode changed
    assert rig.control.mode_of('bend_i') == 'pwm'       # PWM 0: the worm gear holds
    assert last[tables.element('camera_tilt').index] == 7 * 43   # the operator's camera
    assert not rig.setpoint.enabled


def test_rewind_toggles_only_while_stopped(rig):
    rig.press(REWIND)
    assert rig.mapper.operation_mode == 'pab' and rig.leds[REWIND] is True
    rig.play()
    rig.press(REWIND)
    assert rig.mapper.operation_mode == 'pab'
    assert any('press Stop first' in line for line in rig.logs)
    rig.press(STOP)
    rig.press(REWIND)
    assert rig.mapper.operation_mode == 'manual' and rig.leds[REWIND] is False


def test_pab_mode_ignores_joint_controls_but_not_camera(rig):
    rig.press(REWIND)
    rig.play()
    rig.mapper.handle(SLIDER_BEND_I, 127)
    rig.mapper.handle(SLIDER_BEND_I, 0)
    rig.mapper.handle(SLIDER_CAMERA_TILT, 0)
    rig.mapper.handle(21, 0)
    assert rig.setpoint.get('bend_i') == 0
    assert rig.setpoint.get('camera_tilt') == 252 and rig.setpoint.get('camera_pan') == 252
    told = [line for line in rig.logs if 'joint controls are ignored' in line]
    assert len(told) == 1
    rig.press(STOP)
    rig.press(REWIND)
    rig.press(REWIND)
    rig.play()
    rig.mapper.handle(SLIDER_BEND_I, 127)
    assert len([line for line in rig.logs if 'joint controls are ignored' in line]) == 2


def test_operation_mode_switch_keeps_setpoints(rig):
    rig.play()
    rig.press(S_CAMERA_TILT)
    rig.mapper.handle(SLIDER_CAMERA_TILT, 20)   # camera position, kept over Stop
    rig.press(STOP)
    before = rig.setpoint.get_all()
    rig.press(REWIND)
    rig.play()
    assert rig.setpoint.get_all() == before
    assert rig.setpoint.get('camera_tilt') == 7 * 43


def test_play_after_mode_switch_sends_no_motion(rig):
    rig.play()
    rig.mapper.handle(SLIDER_BEND_I, 127)   # PWM: motion
    rig.mapper.handle(SLIDER_DRIVE, 127)
    rig.press(STOP)
    rig.press(REWIND)
    rig.play()
    sent = rig.setpoint.tick()
    assert sent[tables.element('bend_i').index] == 0 and sent[tables.element('wheels').index] == 0


def test_control_mode_switch_keeps_setpoint_within_new_limits(rig):
    rig.play()
    rig.press(S_CAMERA_TILT)                  # position
    rig.mapper.handle(SLIDER_CAMERA_TILT, 0)  # 441 counts: legal in position mode
    rig.press(S_CAMERA_TILT)                  # back to PWM: 441 is no duty
    assert rig.setpoint.get('camera_tilt') == safety.DUTY_MAX


def test_track_next_sends_clamp_straight_and_refuses_a_second(rig):
    rig.press(REWIND)
    rig.play()
    rig.press(TRACK_NEXT)
    assert rig.pab.goals == [(0, 0.0, 0.0, 0)] and rig.leds[TRACK_NEXT] is True
    rig.press(TRACK_NEXT)
    assert len(rig.pab.goals) == 1
    assert any('a PAB is running' in line for line in rig.logs)
    rig.press(STOP)
    assert rig.pab.cancels == 1
    for _ in range(8):                        # the refusal's blink, then its state
        rig.mapper.tick()
    assert rig.leds[TRACK_NEXT] is False


def test_track_next_refused_in_manual_and_while_stopped(rig):
    rig.press(TRACK_NEXT)
    assert rig.pab.goals == []
    rig.press(REWIND)
    rig.press(TRACK_NEXT)
    assert rig.pab.goals == []
    assert any('press Play first' in line for line in rig.logs)


def test_set_plus_r_calibrates_and_r_alone_does_not(rig):
    rig.play()
    rig.press(R_BEND_I)
    index = tables.element('bend_i').index
    assert rig.control.get(index) != safety.COMMAND_CODES['calibrate']
    rig.mapper.handle(SET, PRESS)
    rig.press(R_BEND_I)
    rig.mapper.handle(SET, RELEASE)
    assert rig.control.get(index) == safety.COMMAND_CODES['calibrate']


def test_set_plus_record_sends_no_limits_all_once_per_press(rig):
    rig.play()
    rig.mapper.handle(SET, PRESS)
    rig.press(RECORD)
    rig.press(RECORD)
    codes = [m[tables.element('rear_module').index] for m in rig.control_pub.messages]
    assert codes.count(safety.COMMAND_CODES['no_limits_all']) == 2
    assert codes[-1] == safety.COMMAND_CODES['play']


@pytest.mark.parametrize('channel,value,reason', [
    (99, 64, 'not on the panel map'), (SLIDER_BEND_I, 300, 'outside 0-127'),
    (SLIDER_BEND_I, -1, 'outside 0-127'), (SLIDER_BEND_I, 1.5, 'integers'),
    (0, 127, 'not used')])
def test_bad_input_logged_once_and_ignored(rig, channel, value, reason):
    rig.play()
    before = rig.setpoint.get_all()
    for _ in range(3):
        rig.mapper.handle(channel, value)
    assert rig.setpoint.get_all() == before
    assert len([line for line in rig.logs if reason in line]) == 1


def test_burst_is_ignored_but_stop_still_works(rig):
    rig.play()
    for i in range(2000):
        rig.mapper.handle(SLIDER_BEND_I, 63 + (i % 2))
    rig.mapper.handle(SLIDER_BEND_I, 127)     # still inside the burst second
    assert rig.setpoint.get('bend_i') != 256
    assert len([line for line in rig.logs if 'events per second' in line]) == 1
    rig.mapper.handle(STOP, PRESS)
    assert not rig.mapper.playing
    rig.clock.now += 1.5
    rig.play()
    rig.mapper.handle(SLIDER_BEND_I, 127)
    assert rig.setpoint.get('bend_i') == 256


def test_tick_follows_modes_changed_by_someone_else(rig):
    rig.control.set_mode('bend_ii', 'torque')    # e.g. a PAB switched it
    rig.mapper.tick()
    assert rig.leds[35] is True


# --- every PAB from the panel, refusals shown, the panel's authority ---

PAB_BUTTONS = {   # channel: (PAB code, distance mm, speed mm/s, option code), config/nanokontrol2.yaml
    59: (0, 0.0, 0.0, 0),        # track >: Clamp Straight
    58: (5, 0.0, 0.0, 0),        # track <: Home
    62: (4, 50.0, 0.0, 0),       # marker >: Drive forwards
    61: (4, -50.0, 0.0, 0),      # marker <: Drive backwards
    44: (2, 0.0, 0.0, 3),        # fast forward: T-joint straight on (not built: the server refuses)
}


@pytest.mark.parametrize('button', sorted(PAB_BUTTONS))
def test_every_pab_button_sends_its_goal(rig, button):
    rig.press(REWIND)
    rig.play()
    rig.press(button)
    assert rig.pab.goals == [PAB_BUTTONS[button]]
    assert rig.leds[button] is True


def test_a_refused_pab_button_blinks_and_says_why(rig):
    rig.press(REWIND)
    rig.press(TRACK_NEXT)                     # before Play
    assert rig.pab.goals == [] and any('refused: press Play first' in line for line in rig.logs)
    seen = []
    for _ in range(10):
        rig.mapper.tick()
        seen.append(rig.leds.get(TRACK_NEXT))
    assert seen[:6] == [True, False, True, False, True, False]    # three blinks
    assert seen[6:] == [False] * 4                               # then its state again


def test_a_pab_that_did_not_succeed_blinks_its_button(rig):
    rig.press(REWIND)
    rig.play()
    rig.press(TRACK_NEXT)
    rig.pab.active = False
    rig.mapper.tick()                         # the server is idle before its result arrives
    rig.mapper.pab_result(False, 'Clamp Straight aborted in clamping rear: timed out')
    assert any('aborted in clamping rear' in line for line in rig.logs)
    rig.mapper.tick()
    rig.mapper.tick()
    assert rig.leds[TRACK_NEXT] is False
    rig.mapper.tick()
    assert rig.leds[TRACK_NEXT] is True       # blinking, not steady


def test_the_panel_refuses_goals_while_stopped(rig):
    assert 'stopped' in rig.mapper.goal_refusal() and 'Play' in rig.mapper.goal_refusal()
    rig.play()
    assert rig.mapper.goal_refusal() is None
    rig.press(STOP)
    assert 'stopped' in rig.mapper.goal_refusal()


def test_stop_cancels_another_clients_goal_in_manual_mode(rig):
    rig.play()
    rig.pab.active = True                     # a goal from a terminal runs
    rig.press(STOP)
    assert rig.pab.cancels == 1


MARK_FINDING = 32      # S 1


class FakeFinding(object):
    def __init__(self):
        self.notes = []

    def mark(self, note):
        self.notes.append(note)


@pytest.mark.parametrize('pab_mode', [False, True])
def test_the_mark_button_marks_one_finding_per_press_in_either_mode(rig, pab_mode):
    finding = FakeFinding()
    rig.mapper = Mapper(panel_config.load(CONFIG), rig.setpoint, rig.control, rig.limit, rig.pab,
                        rig.leds.__setitem__, rig.logs.append, rig.clock, finding=finding)
    if pab_mode:
        rig.press(REWIND)
    rig.mapper.handle(MARK_FINDING, PRESS)
    rig.mapper.handle(MARK_FINDING, PRESS)          # held: one press
    rig.mapper.handle(MARK_FINDING, RELEASE)
    rig.press(MARK_FINDING)
    assert finding.notes == ['marked from the panel (S 1)'] * 2


def test_the_mark_button_without_a_recorder_tells_the_operator(rig):
    rig.press(MARK_FINDING)
    assert rig.logs[-1] == 'S 1: no inspection recorder to mark a finding with'
