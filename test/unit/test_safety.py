"""pirate.robot.safety: every limit on what goes to the robot (SPEC 3, 7)."""
import math

import pytest

from pirate.robot import safety, tables

BENDS = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')
DUTY_ELEMENTS = ('camera_tilt', 'front_tilt', 'camera_pan', 'front_led', 'rear_led') + BENDS


@pytest.mark.parametrize('name', DUTY_ELEMENTS)
@pytest.mark.parametrize('mode', ['pwm', 'torque'])
def test_pwm_and_torque_setpoints_are_limited_to_256(name, mode):
    if mode == 'torque' and name not in BENDS:
        mode = 'pwm'
    assert safety.limit_setpoint(name, mode, 256) == (256, None)
    assert safety.limit_setpoint(name, mode, -256) == (-256, None)
    counts, reason = safety.limit_setpoint(name, mode, 257)
    assert counts == 256 and name in reason and 'clamped' in reason
    counts, reason = safety.limit_setpoint(name, mode, -1000)
    assert counts == -256 and reason


def test_wheel_velocity_limited_to_170_mm_s():
    top = round(170 / 0.083 * 0.02)          # counts per 20 ms sample
    assert safety.limit_setpoint('wheels', 'velocity', top) == (top, None)
    counts, reason = safety.limit_setpoint('wheels', 'velocity', top + 1)
    assert counts == top and reason
    counts, reason = safety.limit_setpoint('wheels', 'velocity', -200)
    assert counts == -top and reason


def test_wheel_pwm_uses_the_duty_range():
    assert safety.limit_setpoint('wheels', 'pwm', 200) == (200, None)
    assert safety.limit_setpoint('wheels', 'pwm', 300)[0] == 256


def test_rotation_limited_to_0_7_rad():
    top = round(0.7 * 2133.33)
    assert safety.limit_setpoint('rotation', 'position', top) == (top, None)
    assert safety.limit_setpoint('rotation', 'position', -top) == (-top, None)
    counts, reason = safety.limit_setpoint('rotation', 'position', top + 1)
    assert counts == top and reason
    assert safety.limit_setpoint('rotation', 'position', -5000)[0] == -top
    assert safety.rotation_ok(0.7) and safety.rotation_ok(-0.7)
    assert not safety.rotation_ok(0.71) and not safety.rotation_ok(float('nan'))


def test_position_setpoints_half_a_turn():
    assert safety.limit_setpoint('front_tilt', 'position', 2048) == (2048, None)
    assert safety.limit_setpoint('camera_tilt', 'position', -3000)[0] == -2048


@pytest.mark.parametrize('bad', [float('nan'), float('inf'), -float('inf'), 'ten', None])
def test_non_numbers_are_refused(bad):
    with pytest.raises(safety.Refused):
        safety.limit_setpoint('bend_i', 'torque', bad)
    with pytest.raises(safety.Refused):
        safety.limit_torque_limit('bend_i', bad)


def test_unknown_element_is_a_key_error():
    with pytest.raises(KeyError):
        safety.limit_setpoint('bend_v', 'pwm', 0)


def test_fractional_setpoints_round_to_counts():
    assert safety.limit_setpoint('bend_i', 'torque', 10.6) == (11, None)


@pytest.mark.parametrize('code', [-1, 11, 12, 255, 32767])
def test_unknown_control_code_is_refused(code):
    with pytest.raises(safety.Refused, match='not a mode or command'):
        safety.check_control_code(2, code)


@pytest.mark.parametrize('code', range(11))
def test_every_known_code_is_accepted(code):
    safety.check_control_code(0, code)


@pytest.mark.parametrize('index', [-1, 12, 13])
def test_control_index_outside_the_array_is_refused(index):
    with pytest.raises(safety.Refused):
        safety.check_control_code(index, 0)


def test_control_codes_match_the_message_constants():
    from pirate.msg import ControlArray
    expected = {'pwm': ControlArray.PWM, 'velocity': ControlArray.VELOCITY,
                'position': ControlArray.POSITION, 'torque': ControlArray.TORQUE,
                'current': ControlArray.CURRENT}
    assert safety.MODE_CODES == expected
    assert safety.COMMAND_CODES == {
        'calibrate': ControlArray.CALIBRATE, 'torque_limit': ControlArray.TORQUE_LIMIT,
        'play': ControlArray.PLAY, 'stop': ControlArray.STOP,
        'no_limits_all': ControlArray.NO_LIMITS_ALL, 'single_stop': ControlArray.SINGLE_STOP}
    # SPEC 3 numbers, typed independently
    assert [expected[k] for k in ('pwm', 'velocity', 'position', 'torque', 'current')] == [0, 1, 2, 3, 4]


@pytest.mark.parametrize('name', BENDS)
def test_torque_limits_are_uint16(name):
    assert safety.limit_torque_limit(name, 0) == (0, None)
    assert safety.limit_torque_limit(name, 65535) == (65535, None)
    assert safety.limit_torque_limit(name, 70000)[0] == 65535
    counts, reason = safety.limit_torque_limit(name, -3)
    assert counts == 0 and reason
    assert safety.NO_LIMIT == 0xFFFF


def test_torque_limit_only_for_bends():
    with pytest.raises(KeyError):
        safety.limit_torque_limit('front_tilt', 10)


def test_drive_speed_ok():
    assert safety.drive_speed_ok(170) and safety.drive_speed_ok(-170)
    assert not safety.drive_speed_ok(170.1)
    assert not safety.drive_speed_ok(math.inf) and not safety.drive_speed_ok(math.nan)


def test_every_setpoint_element_has_a_range():
    for elem in tables.SETPOINT_ELEMENTS:
        counts, _ = safety.limit_setpoint(elem.name, 'pwm', 10 ** 6)
        assert 0 < counts <= 2048
