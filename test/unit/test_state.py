"""StateAssembler: Small State (raw, Table B.1) -> SI snapshot, bad input, staleness."""
import math

import pytest

from pirate.robot import tables, units
from pirate.state.assembler import BadState, StateAssembler


def raw(angle=0, bend_load=0, odometry=0, velocity=0, board=None):
    """A board's Small State; board 25 (the IMU's, a drive board too) reads upright."""
    data = imu(math.pi / 2) if board == tables.IMU_BOARD else [0] * 9
    data[tables.SS_ODOMETRY] = odometry
    data[tables.SS_VELOCITY] = velocity
    data[tables.SS_ANGLE] = angle
    data[tables.SS_BEND_LOAD] = bend_load
    return data


def imu(roll):
    data = [0] * 9
    g_y, g_z = units.roll_to_gravity(roll)
    data[tables.SS_IMU_Y], data[tables.SS_IMU_Z] = int(round(g_y)), int(round(g_z))
    return data


def full_cycle(state, now, angles=None, roll=math.pi / 2):
    """Feed one refresh cycle, boards 20..28; return the completion flags."""
    angles = angles or {}
    flags = []
    for board in tables.BOARDS:
        data = imu(roll) if board == tables.IMU_BOARD else raw(angles.get(board, 0))
        flags.append(state.update(board, data, now))
    return flags


def position(snap, name):
    return snap.position[snap.name.index(name)]


def test_conversions_to_si():
    state = StateAssembler()
    full_cycle(state, 0.0, angles={22: -512, 23: 256, 24: 2133, 21: 300}, roll=0.3)
    state.update(26, raw(angle=100, bend_load=500), 0.0)
    snap = state.snapshot(0.05)
    assert position(snap, 'bend_i') == pytest.approx(-512 * 2 * math.pi / 4096)
    assert position(snap, 'bend_ii') == pytest.approx(math.pi * 256 / 2048)
    assert position(snap, 'rotation') == pytest.approx(2133 / 2133.33)
    assert position(snap, 'front_tilt') == pytest.approx(300 * 2 * math.pi / 4096)
    assert position(snap, 'bend_iii') == pytest.approx(100 * 2 * math.pi / 4096)
    effort = snap.effort[snap.name.index('bend_iii')]
    assert effort == pytest.approx(math.degrees(500 * 2 * math.pi / 4096) / (58 / 16.0) * 41.6)
    assert snap.orientation == pytest.approx(0.3, abs=1e-3)
    assert snap.stale is False and snap.age == pytest.approx(0.05)


def test_velocity_is_the_median_of_the_drive_boards():
    """One wheel spinning free (board 22 at 60) is not the robot's speed."""
    state = StateAssembler()
    for board, counts in zip(tables.DRIVE_BOARDS, (60, 36, 36, 37, 35, 36)):
        state.update(board, raw(velocity=counts, board=board), 0.0)
    assert state.snapshot(0.0).velocity == pytest.approx(36 * 0.083 / 0.02)


@pytest.mark.parametrize('board,data,reason', [
    (19, [0] * 9, 'unknown board'),
    (29, [0] * 9, 'unknown board'),
    (22, [0] * 8, 'elements'),
    (22, [0] * 10, 'elements'),
    (22, raw(angle=2049), 'AS5055'),
    (27, raw(angle=-3000), 'AS5055'),
    (25, [0] * 9, 'not gravity'),
    (25, [0, 0, 0, 0, 32000, 32000, 0, 0, 0], 'not gravity'),
    (25, [0, 0, 0, 20000, 16384, 0, 0, 0, 0], 'not gravity'),   # 1.6 g: y alone is 1 g
])
def test_bad_small_state_dropped_old_values_kept(board, data, reason):
    state = StateAssembler()
    full_cycle(state, 0.0, angles={22: 100, 27: -200}, roll=1.0)
    before = state.snapshot(0.0)
    with pytest.raises(BadState, match=reason):
        state.update(board, data, 0.01)
    after = state.snapshot(0.0)
    assert after.position == before.position
    assert after.orientation == before.orientation
    assert state.age(0.0) == 0.0     # the dropped message did not refresh anything


def pitched_imu(roll, pitch):
    """Board 25's reading with the rear part pitched ``pitch`` rad (up a pipe):
    gravity along the robot's axis (x) grows, its (y, z) part shrinks."""
    data = imu(roll)
    data[tables.SS_IMU_Y] = int(round(data[tables.SS_IMU_Y] * math.cos(pitch)))
    data[tables.SS_IMU_Z] = int(round(data[tables.SS_IMU_Z] * math.cos(pitch)))
    data[tables.SS_IMU_X] = int(round(units.IMU_COUNTS_PER_G * math.sin(pitch)))
    return data


@pytest.mark.parametrize('pitch_deg', [30, 59])
def test_a_pitched_robot_reads_its_roll(pitch_deg):
    """Gravity is judged on all three axes: a robot on a slope is not a
    silent IMU, and its roll comes from gravity's (y, z) part."""
    state = StateAssembler()
    full_cycle(state, 0.0, roll=math.pi / 2)
    state.update(tables.IMU_BOARD, pitched_imu(1.2, math.radians(pitch_deg)), 0.05)
    assert state.snapshot(0.05).orientation == pytest.approx(1.2, abs=0.01)


@pytest.mark.parametrize('pitch_deg', [61, 80, 90])
def test_a_steeply_pitched_robot_holds_its_last_roll(pitch_deg):
    """Pitched over 60 deg (a pipe going up) the roll is not defined: the
    reading is gravity, so it is kept, but the last roll is held."""
    state = StateAssembler()
    full_cycle(state, 0.0, roll=1.3)
    state.update(tables.IMU_BOARD, pitched_imu(0.2, math.radians(pitch_deg)), 0.05)
    snap = state.snapshot(0.05)
    assert snap.orientation == pytest.approx(1.3, abs=0.01)
    assert tables.IMU_BOARD not in state.silent(0.05)


def test_staleness_by_the_time_passed_in():
    state = StateAssembler(stale_after=0.3)
    assert state.snapshot(0.0).stale is True
    assert state.age(5.0) == float('inf')
    full_cycle(state, 10.0)
    assert state.snapshot(10.29).stale is False
    snap = state.snapshot(10.31)
    assert snap.stale is True and snap.age == pytest.approx(0.31)
    full_cycle(state, 10.4)
    assert state.snapshot(10.5).stale is False


def test_odometry_unwraps_across_int16_wrap():
    """Counted from the first reading; each cycle adds the drive boards' median step."""
    state = StateAssembler()
    forward = [32000, 32700, -32700, -32000]       # +700, +136 (across the wrap), +700
    for t, value in enumerate(forward):
        for board in tables.BOARDS:
            state.update(board, raw(odometry=value, board=board), float(t))
    assert state.snapshot(4.0).odometry == pytest.approx((700 + 136 + 700) * 0.083)
    for board in tables.BOARDS:
        state.update(board, raw(odometry=32700, board=board), 5.0)
    assert state.snapshot(5.0).odometry == pytest.approx((32700 - 32000) * 0.083)   # -836 back across


def test_cycle_completion():
    state = StateAssembler()
    flags = full_cycle(state, 0.0)
    assert flags == [False] * 8 + [True]
    # the next cycle's first board completes nothing: one state per cycle
    # (a second one would let a simulator in lockstep count it for the next cycle)
    assert full_cycle(state, 0.1) == [False] * 8 + [True]
    # a cycle that misses board 28 completes when the next cycle starts again
    for board in tables.BOARDS[:-1]:
        assert state.update(board, imu(1.0) if board == tables.IMU_BOARD else raw(), 0.2) is False
    assert state.update(tables.BOARDS[0], raw(), 0.3) is True


def test_no_data_yet_gives_zero_angles_and_stale():
    snap = StateAssembler().snapshot(0.0)
    assert snap.position == [0.0] * len(tables.JOINT_NAMES)
    assert snap.stale is True and snap.name == list(tables.JOINT_NAMES)
