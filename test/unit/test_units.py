"""pirate.robot.units: conversions both ways, int16 wrap, gravity <-> roll."""
import math

import pytest

from pirate.robot import units


@pytest.mark.parametrize('rad', [-math.pi, -1.0, -0.77, 0.0, 0.35, 1.0, math.pi - 0.001])
def test_encoder_round_trip_within_one_count(rad):
    counts = units.rad_to_encoder(rad)
    assert isinstance(counts, int)
    assert abs(units.encoder_to_rad(counts) - rad) <= 0.5 * 2 * math.pi / 4096 + 1e-12


def test_encoder_is_4096_counts_per_turn():
    assert units.rad_to_encoder(2 * math.pi) == 4096
    assert units.rad_to_encoder(-math.pi / 2) == -1024
    assert units.encoder_to_rad(1024) == pytest.approx(math.pi / 2)


def test_rotation_is_2133_33_counts_per_rad():
    assert units.rad_to_rotation(1.0) == 2133
    assert units.rad_to_rotation(-0.7) == -1493
    assert units.rotation_to_rad(2133.33) == pytest.approx(1.0)
    for rad in (-0.7, -0.1, 0.0, 0.0425, 0.7):
        assert units.rotation_to_rad(units.rad_to_rotation(rad)) == pytest.approx(rad, abs=1 / 2133.33)


def test_wheel_velocity_counts_per_pico_sample():
    # SPEC 3: v [mm/s] / 0.083 * 0.02
    assert units.mm_s_to_wheel_counts(170) == round(170 / 0.083 * 0.02) == 41
    assert units.mm_s_to_wheel_counts(-150) == -36
    assert units.wheel_counts_to_mm_s(41) == pytest.approx(41 * 0.083 / 0.02)
    for mm_s in (-170, -50, 0, 12.5, 150):
        back = units.wheel_counts_to_mm_s(units.mm_s_to_wheel_counts(mm_s))
        assert back == pytest.approx(mm_s, abs=0.083 / 0.02 / 2 + 1e-9)


def test_odometry_mm_per_count():
    assert units.odometry_to_mm(1000) == pytest.approx(83.0)
    assert units.odometry_to_mm(-12) == pytest.approx(-0.996)


@pytest.mark.parametrize('mnm', [-400.0, -41.6, 0.0, 100.0, 409.6])
def test_spring_effort_round_trip(mnm):
    counts = units.mnm_to_spring(mnm)
    # one spring-encoder count is worth 360/4096/(58/16) deg at the joint
    one_count_mnm = 360.0 / 4096 / (58.0 / 16.0) * 41.6
    assert units.spring_to_mnm(counts) == pytest.approx(mnm, abs=one_count_mnm / 2 + 1e-9)


def test_spring_constant_41_6_mnm_per_joint_degree():
    # one joint degree is 58/16 degrees at the spring encoder
    counts_per_joint_deg = 4096 / 360.0 * 58.0 / 16.0
    assert units.spring_to_mnm(counts_per_joint_deg) == pytest.approx(41.6)


@pytest.mark.parametrize('value,wrapped', [
    (0, 0), (32767, 32767), (32768, -32768), (-32768, -32768), (-32769, 32767),
    (65536, 0), (70000, 70000 - 65536), (-100000, -100000 + 2 * 65536)])
def test_wrap_int16(value, wrapped):
    assert units.wrap_int16(value) == wrapped


@pytest.mark.parametrize('previous,step', [
    (0, 5), (32760, 20), (-32760, -20), (32000, -1500), (100, 30000), (-5, -32768 + 6)])
def test_unwrap_int16_recovers_the_step_across_the_wrap(previous, step):
    raw = units.wrap_int16(previous + step)
    assert units.unwrap_int16(previous, raw) == step


def test_roll_upright_is_all_z_and_on_right_side_all_y():
    g_y, g_z = units.roll_to_gravity(math.pi / 2)
    assert (g_y, g_z) == pytest.approx((0.0, units.IMU_COUNTS_PER_G), abs=1e-9)
    g_y, g_z = units.roll_to_gravity(0.0)
    assert (g_y, g_z) == pytest.approx((units.IMU_COUNTS_PER_G, 0.0), abs=1e-9)


@pytest.mark.parametrize('step', range(72))
def test_gravity_roll_round_trip_over_the_whole_circle(step):
    roll = -math.pi / 2 + step * 2 * math.pi / 72     # [-pi/2, 3pi/2)
    g_y, g_z = units.roll_to_gravity(roll)
    assert math.hypot(g_y, g_z) == pytest.approx(units.IMU_COUNTS_PER_G)
    back = units.gravity_to_roll(g_y, g_z)
    assert -math.pi / 2 <= back < 3 * math.pi / 2
    assert back == pytest.approx(roll, abs=1e-9)


def test_gravity_roll_does_not_wrap_in_the_working_region():
    rolls = [units.gravity_to_roll(*units.roll_to_gravity(r / 10.0)) for r in range(0, 32)]
    assert rolls == sorted(rolls)
