"""The fast fake robot for unit tests (pirate.sim.fake_robot: fitted, not physics), without ROS.

Expected figures are the report's (SPEC 7, 10; Tables 5.2, 5.3, 6.5), never
values read back from the model's own constants.
"""
import math

import pytest

from pirate.robot import safety, tables, units
from pirate.sim import fake_robot as sim

UPRIGHT = math.pi / 2
DT = 0.02                      # one PICO sample
IDX = {e.name: e.index for e in tables.SETPOINT_ELEMENTS}
MODE = safety.MODE_CODES
CMD = safety.COMMAND_CODES
# Report guards (Table 5.2, 5.3), rad: (outer, inner)
FULL_90, FULL_110, CUSTOM_90 = (-0.77, 0.35), (-1.25, 0.65), (-0.68, 0.33)


class Robot(object):
    """Drives a FakeRobot through its three arrays, as the Mega would."""

    def __init__(self, **kwargs):
        self.model = sim.FakeRobot(**kwargs)
        self.setpoints = [0] * tables.SETPOINT_SIZE
        self.modes = [MODE['pwm']] * tables.CONTROL_SIZE
        self.limits = [safety.NO_LIMIT] * tables.LIMIT_SIZE

    def send(self):
        return self.model.command(self.setpoints, self.modes, self.limits)

    def mode(self, name, mode):
        self.modes[IDX[name]] = MODE[mode]
        return self.send()

    def cmd(self, name):
        self.modes[IDX['rear_module']] = CMD[name]
        return self.send()

    def set(self, **setpoints):
        for name, value in setpoints.items():
            self.setpoints[IDX[name]] = value
        return self.send()

    def run(self, seconds):
        for _ in range(int(round(seconds / DT))):
            self.model.step(DT)

    def angle(self, name):
        return self.model.joint_angles[name]

    def clamp(self, part, seconds=8.0):
        outer, inner = sim.CLAMPS[part]
        self.mode(outer, 'torque')
        self.mode(inner, 'torque')
        self.set(**{outer: 256, inner: -256})
        self.run(seconds)
        return self.angle(outer), self.angle(inner)


def playing(**kwargs):
    robot = Robot(**kwargs)
    robot.cmd('play')
    return robot


# --- geometry ---------------------------------------------------------------

def test_clamp_in_90_mm_reaches_the_report_angles():
    outer, inner = playing(pipe_diameter=90).clamp('rear')
    assert outer <= FULL_90[0] and inner >= FULL_90[1]          # the guards are reachable
    assert outer == pytest.approx(-0.835, abs=0.1)              # Table 6.5 averages
    assert inner == pytest.approx(0.43, abs=0.1)


def test_clamp_in_110_mm_bends_further_than_in_90():
    out90, in90 = playing(pipe_diameter=90).clamp('front')
    out110, in110 = playing(pipe_diameter=110).clamp('front')
    assert out110 < out90 - 0.2 and in110 > in90 + 0.1
    assert out110 <= FULL_110[0] and in110 >= FULL_110[1]


def test_clamp_angles_depend_on_pipe_only_through_geometry():
    assert sim.clamp_half_angle(0.11, UPRIGHT) > sim.clamp_half_angle(0.09, UPRIGHT)
    # a pipe narrower than a wheel leaves no room to bend
    assert sim.clamp_half_angle(0.04, UPRIGHT) == 0.0


@pytest.mark.parametrize('roll', [0.0, math.pi])
def test_lying_on_a_side_reaches_smaller_angles(roll):
    upright = playing(pipe_diameter=90).clamp('rear')
    side = playing(pipe_diameter=90, orientation=roll).clamp('rear')
    assert side[0] > upright[0] + 0.05 and side[1] < upright[1] - 0.03
    # the report needed custom guards on its side (Table 5.3), not the full ones
    assert side[0] <= CUSTOM_90[0] and side[1] >= CUSTOM_90[1]
    assert not (side[0] <= FULL_90[0] and side[1] >= FULL_90[1])


def test_chord_shrinks_monotonically_towards_the_side():
    angles = [sim.clamp_half_angle(0.09, UPRIGHT - k * 0.2) for k in range(8)]
    assert angles == sorted(angles, reverse=True)


# --- which part turns -------------------------------------------------------

def rotate(robot, rad, seconds=4.0):
    robot.mode('rotation', 'position')
    robot.set(rotation=units.rad_to_rotation(rad))
    robot.run(seconds)


def test_rotation_with_rear_clamped_turns_only_the_front():
    robot = playing()
    robot.clamp('rear')
    assert robot.model.clamped('rear') and not robot.model.clamped('front')
    rotate(robot, 0.3)
    assert robot.model.rotation == pytest.approx(0.3, abs=0.01)
    assert robot.model.rear_roll == pytest.approx(UPRIGHT)
    assert robot.model.front_roll == pytest.approx(UPRIGHT - 0.3, abs=0.01)


def test_rotation_with_front_clamped_turns_the_rear_and_the_imu():
    robot = playing()
    robot.clamp('front')
    rotate(robot, -0.3)
    assert robot.model.rear_roll == pytest.approx(UPRIGHT - 0.3, abs=0.01)
    assert robot.model.front_roll == pytest.approx(UPRIGHT, abs=1e-9)
    imu = robot.model.small_state(tables.IMU_BOARD)
    assert units.gravity_to_roll(imu[tables.SS_IMU_Y], imu[tables.SS_IMU_Z]) == \
        pytest.approx(UPRIGHT - 0.3, abs=0.01)


def test_rotation_stalls_when_both_parts_are_clamped():
    robot = playing()
    robot.clamp('front')
    robot.clamp('rear')
    rotate(robot, 0.3)
    assert robot.model.rotation == 0.0 and robot.model.rear_roll == UPRIGHT


# --- PLAY / STOP ---------------------------------------------------------------

def test_nothing_moves_before_play():
    robot = Robot()
    robot.mode('bend_i', 'torque')
    robot.set(front_tilt=128, bend_i=256, wheels=100)
    before = dict(robot.model.joint_angles)
    robot.run(2.0)
    assert robot.model.joint_angles == before
    assert robot.model.wheel_mm_s == 0.0


def test_nothing_moves_after_stop():
    robot = playing()
    robot.set(front_tilt=64)
    robot.run(0.5)
    assert robot.angle('front_tilt') > 0.05
    robot.cmd('stop')
    held = dict(robot.model.joint_angles)
    robot.run(2.0)
    assert robot.model.joint_angles == held


def test_single_stop_halts_one_joint():
    robot = playing()
    robot.set(front_tilt=64, camera_tilt=64)
    robot.modes[IDX['front_tilt']] = CMD['single_stop']
    robot.send()
    robot.run(1.0)
    assert robot.angle('front_tilt') == 0.0 and robot.angle('camera_tilt') > 0.1


# --- each motor obeys its control mode (Table 2.1) -------------------------

def test_pwm_speed_proportional_to_duty():
    moved = {}
    for duty in (16, 32, -32):
        robot = playing()
        robot.set(front_tilt=duty)
        robot.run(1.0)
        moved[duty] = robot.angle('front_tilt')
    assert moved[16] > 0.02
    assert moved[32] == pytest.approx(2 * moved[16], rel=0.02)
    assert -0.1 < moved[-32] < 0        # down, until its mechanical stop just past straight


@pytest.mark.parametrize('name,target', [('front_tilt', 0.6), ('camera_tilt', -0.4),
                                         ('camera_pan', 0.8)])
def test_position_mode_converges_to_target(name, target):
    robot = playing()
    robot.mode(name, 'position')
    robot.set(**{name: units.rad_to_encoder(target)})
    robot.run(1.0)
    assert abs(robot.angle(name) - target) > 0.01      # it takes time
    robot.run(5.0)
    assert robot.angle(name) == pytest.approx(target, abs=0.005)


def test_torque_bends_close_until_the_wall_with_effort():
    robot = playing()
    outer, inner = robot.clamp('rear', seconds=8.0)
    robot.run(1.0)
    assert (robot.angle('bend_iv'), robot.angle('bend_iii')) == (outer, inner)   # at the wall
    ss = robot.model.small_state(27)
    assert units.spring_to_mnm(ss[tables.SS_BEND_LOAD]) > 100       # pressing: spring load
    assert ss[tables.SS_TORQUE] == 256
    robot.set(bend_iii=0)
    robot.run(1.0)
    assert robot.angle('bend_iii') == inner           # worm gear holds without torque
    assert robot.model.small_state(26)[tables.SS_BEND_LOAD] == 0


def test_a_compliant_inner_bend_follows_only_an_outer_driven_closed():
    """Released after a clamp (outer still at its clamp torque) the inner bend
    closes with the outer; after an unclamp, one cycle at torque 0 on the way
    to a worm hold must not move it (seq_mission: the part read partly clamped)."""
    robot = playing()
    robot.mode('bend_iv', 'torque')
    robot.mode('bend_iii', 'torque')
    robot.set(bend_iv=256, bend_iii=0)
    robot.run(2.0)
    assert robot.angle('bend_iii') == pytest.approx(-robot.angle('bend_iv') / 2)   # pushed along
    robot.set(bend_iv=-100, bend_iii=150)                                           # unclamp
    robot.run(6.0)
    opened = robot.angle('bend_iii')
    robot.set(bend_iv=0, bend_iii=0)                  # the zeros of a worm hold, before its PWM mode
    robot.run(DT)
    assert robot.angle('bend_iii') == opened


def test_torque_limit_respected():
    free = playing()
    free.mode('bend_i', 'torque')
    free.set(bend_i=256)
    free.run(1.0)
    limited = playing()
    limited.limits[tables.limit_index('bend_i')] = 50
    limited.mode('bend_i', 'torque')
    limited.set(bend_i=256)
    limited.run(1.0)
    assert free.angle('bend_i') < limited.angle('bend_i') < 0


def test_torque_limit_zero_means_no_motion_but_no_limits_all_overrides():
    robot = playing()
    robot.limits = [0, 0, 0, 0]
    outer, inner = robot.clamp('front', seconds=2.0)
    assert (outer, inner) == (0.0, 0.0)
    robot.cmd('no_limits_all')
    robot.run(1.0)
    assert robot.angle('bend_i') < -0.1


def test_velocity_wheels_and_odometry_only_while_clamped():
    robot = playing()
    robot.mode('wheels', 'velocity')
    robot.set(wheels=units.mm_s_to_wheel_counts(150))
    robot.run(2.0)
    assert robot.model.wheel_mm_s == pytest.approx(150, abs=3)
    assert robot.model.odometry_mm == 0.0                 # spinning free, no traction
    robot.set(wheels=0)
    robot.clamp('rear')
    start = robot.model.odometry_mm
    robot.set(wheels=units.mm_s_to_wheel_counts(150))
    robot.run(3.0)
    travelled = robot.model.odometry_mm - start
    assert 150 * 3.0 * 0.8 < travelled < 150 * 3.0 * 1.02
    ss = robot.model.small_state(tables.DRIVE_BOARDS[0])
    assert units.odometry_to_mm(ss[tables.SS_ODOMETRY]) == pytest.approx(robot.model.odometry_mm, abs=0.1)
    assert units.wheel_counts_to_mm_s(ss[tables.SS_VELOCITY]) == pytest.approx(150, abs=5)


# --- bad input ----------------------------------------------------------------

def test_bad_control_code_keeps_old_mode_with_reason():
    robot = playing()
    robot.mode('bend_ii', 'torque')
    robot.modes[IDX['bend_ii']] = 42
    reasons = robot.send()
    assert len(reasons) == 1 and '42' in reasons[0]
    assert robot.model.modes[IDX['bend_ii']] == MODE['torque']


def test_over_range_setpoint_clamped_with_reason():
    robot = playing()
    reasons = robot.set(front_tilt=5000)
    assert len(reasons) == 1 and 'front_tilt' in reasons[0]
    assert robot.model.setpoints[IDX['front_tilt']] == 256
    robot.mode('rotation', 'position')
    reasons = robot.set(rotation=30000)
    assert any('rotation' in r for r in reasons)
    assert robot.model.setpoints[IDX['rotation']] == units.rad_to_rotation(0.7)


def test_small_state_of_unknown_board_raises():
    with pytest.raises(KeyError):
        Robot().model.small_state(29)


def test_small_state_is_int16_raw_for_every_board():
    robot = playing()
    robot.clamp('rear')
    for board in tables.BOARDS:
        data = robot.model.small_state(board)
        assert len(data) == tables.SMALL_STATE_SIZE
        assert all(isinstance(v, int) and -32768 <= v <= 32767 for v in data)
    assert robot.model.small_state(27)[tables.SS_ANGLE] == units.rad_to_encoder(robot.angle('bend_iv'))


def test_seeded_noise_is_reproducible_and_unseeded_is_exact():
    a, b = Robot(seed=3).model, Robot(seed=3).model
    assert [a.small_state(25) for _ in range(3)] == [b.small_state(25) for _ in range(3)]
    exact = Robot().model.small_state(25)
    assert exact[tables.SS_IMU_Z] == round(units.IMU_COUNTS_PER_G)
