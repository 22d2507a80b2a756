"""Setpoint / Control / Limit (report 4.2-4.4) with a fake publisher."""
import pytest

from pirate.robot import commands, safety, tables, units
from pirate.msg import ControlArray, LimitArray, SetpointArray


class FakePublisher(object):
    """Records every message instead of sending it."""

    def __init__(self):
        self.sent = []

    def publish(self, msg):
        self.sent.append(list(msg.data))


@pytest.fixture
def arrays():
    logs = []
    pubs = {k: FakePublisher() for k in ('setpoint', 'control', 'limit')}
    control = commands.Control(pubs['control'], lambda d: ControlArray(data=d), log=logs.append)
    setpoint = commands.Setpoint(pubs['setpoint'], lambda d: SetpointArray(data=d), control,
                                 log=logs.append)
    limit = commands.Limit(pubs['limit'], lambda d: LimitArray(data=d), log=logs.append)
    return setpoint, control, limit, pubs, logs


def test_set_and_get_by_name_and_board(arrays):
    setpoint, _, _, pubs, _ = arrays
    assert setpoint.set('bend_iii', -100) == -100
    assert setpoint.get('bend_iii') == -100
    assert setpoint.get_all()[6] == -100
    assert setpoint.set_by_board(21, 0, 32) == 32
    assert setpoint.get('front_tilt') == 32
    setpoint.set_by_board(26, 1, 7)            # any drive board -> shared wheels
    assert setpoint.get('wheels') == 7
    assert pubs['setpoint'].sent == []         # writers only mark; tick sends


def test_set_all_and_wrong_length(arrays):
    setpoint, _, _, _, _ = arrays
    values = list(range(13))
    setpoint.set_all(values)
    assert setpoint.get_all() == values
    with pytest.raises(safety.Refused):
        setpoint.set_all([0] * 12)


def test_clamping_logged_once_for_a_burst(arrays):
    setpoint, _, _, _, logs = arrays
    for _ in range(50):
        assert setpoint.set('bend_i', 999) == 256
    assert len(logs) == 1 and 'bend_i' in logs[0]


def test_refused_value_keeps_the_old_one_and_logs_once(arrays):
    setpoint, _, _, _, logs = arrays
    setpoint.set('bend_ii', 40)
    for _ in range(5):
        with pytest.raises(safety.Refused):
            setpoint.set('bend_ii', float('nan'))
    assert setpoint.get('bend_ii') == 40
    assert len(logs) == 1


def test_setpoint_limited_by_the_current_control_mode(arrays):
    setpoint, control, _, _, _ = arrays
    assert setpoint.set('wheels', 100) == 100          # PWM: duty range
    control.set_mode('wheels', 'velocity')
    assert setpoint.set('wheels', 100) == 41           # velocity: 170 mm/s


def test_control_change_published_at_once_and_only_on_change(arrays):
    _, control, _, pubs, _ = arrays
    assert control.set_mode('bend_i', 'torque') is True
    assert len(pubs['control'].sent) == 1
    assert pubs['control'].sent[0][2] == 3
    assert control.set_mode('bend_i', 'torque') is False
    assert len(pubs['control'].sent) == 1
    control.command('play')
    assert pubs['control'].sent[-1][8] == 7 and len(pubs['control'].sent) == 2
    assert control.mode_of('bend_i') == 'torque'
    assert control.get(8) == 7


def test_control_set_all_publishes_once(arrays):
    _, control, _, pubs, _ = arrays
    codes = [3] * 12
    assert control.set_all(codes) is True
    assert control.set_all(codes) is False
    assert pubs['control'].sent == [codes]
    with pytest.raises(safety.Refused):
        control.set_all([3] * 11 + [42])
    assert control.get_all() == codes


def test_whole_array_refusals_are_logged_once_each(arrays):
    setpoint, control, limit, _, logs = arrays
    for _ in range(50):
        for array, values in ((control, [3] * 11 + [42]), (control, [3] * 5),
                              (setpoint, [0] * 12), (limit, [1, 2, 3])):
            with pytest.raises(safety.Refused):
                array.set_all(values)
    assert len(logs) == 4, logs
    assert any('42' in line for line in logs)
    assert any('control array needs 12 values, got 5' in line for line in logs)
    assert any('setpoint array needs 13 values, got 12' in line for line in logs)
    assert any('limit array needs 4 values, got 3' in line for line in logs)


def test_unknown_control_mode_or_code_refused_and_nothing_sent(arrays):
    _, control, _, pubs, logs = arrays
    with pytest.raises(safety.Refused):
        control.set_mode('bend_i', 'warp')
    for _ in range(3):
        with pytest.raises(safety.Refused):
            control.set_code(2, 99)
    assert pubs['control'].sent == []
    assert len(logs) == 2 and 'warp' in logs[0] and '99' in logs[1]   # each reason once


def test_tick_publishes_only_when_enabled(arrays):
    setpoint, _, limit, pubs, _ = arrays
    setpoint.set('front_tilt', 32)
    assert setpoint.tick() is None and limit.tick() is None
    assert pubs['setpoint'].sent == [] and pubs['limit'].sent == []
    setpoint.enabled = limit.enabled = True
    setpoint.tick()
    limit.tick()
    assert pubs['setpoint'].sent[-1][1] == 32
    assert pubs['limit'].sent[-1] == [safety.NO_LIMIT] * 4
    assert setpoint.published == 1


def test_publish_now_bypasses_pacing(arrays):
    setpoint, _, _, pubs, _ = arrays
    setpoint.set('bend_i', 5)
    setpoint.publish_now()
    assert pubs['setpoint'].sent == [[0, 0, 5] + [0] * 10]


def test_limits(arrays):
    _, _, limit, _, logs = arrays
    assert limit.get_all() == [0xFFFF] * 4
    assert limit.set('bend_iv', 100) == 100
    assert limit.get('bend_iv') == 100
    assert limit.get_all()[tables.limit_index('bend_iv')] == 100
    for _ in range(3):
        assert limit.set('bend_i', -5) == 0
    assert len(logs) == 1
    limit.set_all([1, 2, 3, 4])
    assert limit.get_all() == [1, 2, 3, 4]
    with pytest.raises(safety.Refused):
        limit.set_all([1, 2, 3])


def test_the_lights_stay_on_through_the_safe_hold(arrays):
    """An inspection lights the pipe for its frames (pirate_manager ~lights):
    both LEDs at the duty, and the safe hold, which stops every motor,
    leaves them lit."""
    from pirate.robot.hold import safe_hold
    setpoint, control, limit, pubs, _ = arrays
    commands.play(control, setpoint, limit)
    commands.light(control, setpoint, 200)
    assert [setpoint.get(led) for led in commands.LEDS] == [200, 200]
    safe_hold(setpoint, control)
    sent = pubs['setpoint'].sent[-1]
    assert [sent[tables.element(led).index] for led in commands.LEDS] == [200, 200]


@pytest.mark.parametrize('duty', [-1, safety.DUTY_MAX + 1, 12.5, '200', True, None])
def test_a_lights_duty_that_is_not_counts_is_refused(arrays, duty):
    setpoint, control, _, _, _ = arrays
    with pytest.raises(ValueError, match='LED duty .*: a whole number of counts from 0 to %d' % safety.DUTY_MAX):
        commands.light(control, setpoint, duty)
    assert [setpoint.get(led) for led in commands.LEDS] == [0, 0]


def test_the_camera_points_in_position_mode_while_the_robot_plays(arrays):
    """/pirate/camera/point: pan and tilt as the panel's knob and slider send them in position mode."""
    setpoint, control, limit, pubs, _ = arrays
    assert not commands.playing(control)
    commands.play(control, setpoint, limit)
    assert commands.playing(control)
    commands.point_camera(control, setpoint, -1.0, 0.5)
    assert [control.mode_of(joint) for joint in commands.CAMERA_JOINTS] == ['position', 'position']
    assert [setpoint.get(joint) for joint in commands.CAMERA_JOINTS] == [units.rad_to_encoder(-1.0),
                                                                         units.rad_to_encoder(0.5)]
    control.command('stop')
    assert not commands.playing(control)


@pytest.mark.parametrize('pan, tilt, said', [
    (float('nan'), 0.0, 'camera_pan nan: an angle in rad'),
    (0.0, '1', "camera_tilt '1': an angle in rad"),
    (True, 0.0, 'camera_pan True'),
    (3.5, 0.0, 'camera_pan 3.50 rad: beyond half a turn either way'),
])
def test_a_camera_angle_it_cannot_take_is_refused_and_nothing_sent(arrays, pan, tilt, said):
    setpoint, control, _, pubs, _ = arrays
    sent = len(pubs['control'].sent)
    with pytest.raises(ValueError) as refused:
        commands.point_camera(control, setpoint, pan, tilt)
    assert said in str(refused.value)
    assert len(pubs['control'].sent) == sent and [setpoint.get(j) for j in commands.CAMERA_JOINTS] == [0, 0]
