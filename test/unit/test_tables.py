"""pirate.robot.tables against an independent transcription of SPEC Tables 4.1-4.3, B.1.

The expected values below are typed from SPEC.md section 3-4, not computed
from pirate.robot.tables, so a wrong row in either place makes a test fail.
"""
import pytest

from pirate.robot import tables
from pirate.msg import ControlArray, LimitArray, SetpointArray, SmallState

# SPEC Table 4.1: index -> (board, motor, what).
SPEC_SETPOINT = {
    0: (20, 0, 'camera_tilt'),
    1: (21, 0, 'front_tilt'),
    2: (22, 0, 'bend_i'),
    3: (23, 0, 'bend_ii'),
    4: (24, 0, 'imu_module'),
    5: (25, 0, 'rotation'),
    6: (26, 0, 'bend_iii'),
    7: (27, 0, 'bend_iv'),
    8: (28, 0, 'rear_module'),
    9: (20, 1, 'camera_pan'),
    10: (21, 1, 'front_led'),
    11: (22, 1, 'wheels'),
    12: (28, 1, 'rear_led'),
}
# SPEC Table 4.3: limit index -> bend module and its board.
SPEC_LIMITS = [('bend_i', 22), ('bend_ii', 23), ('bend_iii', 26), ('bend_iv', 27)]
# SPEC Table 2.1: boards whose motor 1 is a drive wheel.
SPEC_DRIVE_BOARDS = [22, 23, 24, 25, 26, 27]


def test_boards_are_the_nine_picos_front_to_rear():
    assert list(tables.BOARDS) == list(range(20, 29))


@pytest.mark.parametrize('index', sorted(SPEC_SETPOINT))
def test_setpoint_element_matches_table_4_1(index):
    board, motor, name = SPEC_SETPOINT[index]
    elem = tables.SETPOINT_ELEMENTS[index]
    assert (elem.index, elem.board, elem.motor, elem.name) == (index, board, motor, name)
    assert tables.element(name).index == index
    assert tables.index_of(board, motor) == index


def test_array_sizes_match_messages():
    assert tables.SETPOINT_SIZE == 13 == len(SetpointArray().data)
    assert tables.CONTROL_SIZE == 12 == len(ControlArray().data)
    assert tables.LIMIT_SIZE == 4 == len(LimitArray().data)
    assert tables.SMALL_STATE_SIZE == 9 == len(SmallState().data)


def test_control_array_is_setpoint_array_without_rear_led():
    # Table 4.2: indices 0-11 as in Table 4.1, no rear LED.
    assert tables.element('rear_led').index == tables.CONTROL_SIZE
    assert tables.element('wheels').index == 11
    assert ControlArray.COMMAND_INDEX == tables.element('rear_module').index == 8


@pytest.mark.parametrize('board', SPEC_DRIVE_BOARDS)
def test_every_drive_motor_maps_to_the_shared_wheel_element(board):
    assert tables.index_of(board, 1) == 11


def test_drive_boards_match_table_2_1():
    assert sorted(tables.DRIVE_BOARDS) == SPEC_DRIVE_BOARDS


@pytest.mark.parametrize('limit_index,bend', enumerate(SPEC_LIMITS))
def test_limit_array_matches_table_4_3(limit_index, bend):
    name, board = bend
    assert tables.LIMIT_ELEMENTS[limit_index] == name
    assert tables.limit_index(name) == limit_index
    assert tables.element(name).board == board


@pytest.mark.parametrize('board,motor', [(29, 0), (19, 1), (20, 2), (28, 2)])
def test_index_of_refuses_what_no_table_has(board, motor):
    with pytest.raises(KeyError):
        tables.index_of(board, motor)


def test_unknown_names_raise_key_error_with_the_known_names():
    with pytest.raises(KeyError, match='bend_i'):
        tables.element('bend_v')
    with pytest.raises(KeyError):
        tables.limit_index('front_tilt')


def test_small_state_layout_table_b1():
    # Table B.1, elements numbered from 1 in the report, from 0 here.
    assert (tables.SS_ODOMETRY, tables.SS_VELOCITY, tables.SS_DRIVE_LOAD) == (0, 1, 2)
    assert (tables.SS_ANGLE, tables.SS_BEND_LOAD, tables.SS_TORQUE) == (3, 4, 5)
    # board 25: IMU X, Y, Z, U, V, W in elements 4-9 (zero-based 3-8)
    assert tables.IMU_BOARD == 25
    assert [tables.SS_IMU_X, tables.SS_IMU_Y, tables.SS_IMU_Z,
            tables.SS_IMU_U, tables.SS_IMU_V, tables.SS_IMU_W] == [3, 4, 5, 6, 7, 8]


def test_bend_joints_have_springs_and_their_board():
    springs = {j.name: j.board for j in tables.JOINTS if j.has_spring}
    assert springs == {'bend_i': 22, 'bend_ii': 23, 'bend_iii': 26, 'bend_iv': 27}
    assert tables.BEND_JOINTS == ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')


def test_joint_names_are_unique_and_boards_known():
    assert len(set(tables.JOINT_NAMES)) == len(tables.JOINT_NAMES)
    for joint in tables.JOINTS:
        assert joint.board is None or joint.board in tables.BOARDS
    # the IMU board carries no joint angle (its elements 4-9 are the IMU)
    assert all(j.board != tables.IMU_BOARD for j in tables.JOINTS)


def test_modes_follow_table_2_1():
    modes = {e.name: set(e.modes) for e in tables.SETPOINT_ELEMENTS}
    for bend in ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv'):
        assert modes[bend] == {tables.PWM, tables.TORQUE}
    assert modes['front_tilt'] == {tables.PWM, tables.POSITION}
    assert modes['camera_tilt'] == modes['camera_pan'] == {tables.PWM, tables.POSITION}
    assert modes['rotation'] == {tables.POSITION}
    assert modes['wheels'] == {tables.PWM, tables.VELOCITY}
    assert modes['front_led'] == modes['rear_led'] == {tables.PWM}
