"""The robot's tables, in one place (report Tables 2.1, 4.1-4.3, B.1; SPEC 2-4).

Everything that maps a PICO board and motor to an array index, a joint name
or a Small State element is read from here; no other module repeats these
numbers. Pure Python: no ROS import, so the tables are unit-testable offline.
"""
import collections

#: The nine PICO boards on the RS485 bus, front to rear.
BOARDS = (20, 21, 22, 23, 24, 25, 26, 27, 28)

#: One row of Table 4.1 / 4.2: an element of the setpoint (and control) array.
Element = collections.namedtuple('Element', 'index board motor name modes')

# Modes a motor accepts (Table 2.1). Codes in pirate.msg.ControlArray.
PWM, VELOCITY, POSITION, TORQUE = 'pwm', 'velocity', 'position', 'torque'

#: Table 4.1: setpoint array, 13 elements. ``name`` is the element's role in
#: the robot's language; joints use the joint names of pirate.robot.tables.JOINTS.
SETPOINT_ELEMENTS = (
    Element(0, 20, 0, 'camera_tilt', (PWM, POSITION)),
    Element(1, 21, 0, 'front_tilt', (PWM, POSITION)),
    Element(2, 22, 0, 'bend_i', (PWM, TORQUE)),
    Element(3, 23, 0, 'bend_ii', (PWM, TORQUE)),
    Element(4, 24, 0, 'imu_module', ()),
    Element(5, 25, 0, 'rotation', (POSITION,)),
    Element(6, 26, 0, 'bend_iii', (PWM, TORQUE)),
    Element(7, 27, 0, 'bend_iv', (PWM, TORQUE)),
    Element(8, 28, 0, 'rear_module', ()),
    Element(9, 20, 1, 'camera_pan', (PWM, POSITION)),
    Element(10, 21, 1, 'front_led', (PWM,)),
    Element(11, 22, 1, 'wheels', (PWM, VELOCITY)),
    Element(12, 28, 1, 'rear_led', (PWM,)),
)
SETPOINT_SIZE = len(SETPOINT_ELEMENTS)

#: Table 4.2: the control-mode array is the setpoint array less the rear LED.
#: Index 10 (front LED) is present but unused, index 11 is the wheel drive.
CONTROL_SIZE = 12

#: Table 4.3: torque limits of the four bend modules, in this order.
LIMIT_ELEMENTS = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')
LIMIT_SIZE = len(LIMIT_ELEMENTS)

#: Boards whose motor 1 drives a wheel; the Mega copies element 11 to each.
DRIVE_BOARDS = (22, 23, 24, 25, 26, 27)
#: Adjacent modules are mounted mirrored (SPEC 3): the Mega applies this sign
#: to the shared wheel setpoint per drive board. The report gives no values;
#: this is our assumption, to be checked on the robot: Bend I +, Bend II -,
#: Rotational (both boards) +, Bend III -, Bend IV +.
WHEEL_SIGN = {22: 1, 23: -1, 24: 1, 25: 1, 26: -1, 27: 1}

_BY_NAME = {e.name: e for e in SETPOINT_ELEMENTS}
_BY_BOARD_MOTOR = {(e.board, e.motor): e for e in SETPOINT_ELEMENTS}


def element(name):
    """Return the setpoint :class:`Element` called ``name`` (KeyError if none)."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise KeyError('no setpoint element %r; known: %s'
                       % (name, ', '.join(sorted(_BY_NAME))))


def index_of(board, motor):
    """Setpoint/control array index of (board, motor), per Table 4.1.

    Motor 1 of every drive board maps to the shared wheel element 11.
    """
    if motor == 1 and board in DRIVE_BOARDS:
        return element('wheels').index
    try:
        return _BY_BOARD_MOTOR[(board, motor)].index
    except KeyError:
        raise KeyError('board %r motor %r has no array element' % (board, motor))


def limit_index(name):
    """Index of a bend module in the limit array (Table 4.3)."""
    try:
        return LIMIT_ELEMENTS.index(name)
    except ValueError:
        raise KeyError('%r has no torque limit; only %s' % (name, LIMIT_ELEMENTS))


# --- Joints (what the Pirate State node publishes and the URDF models) -----

#: A joint and where its angle comes from: ``board`` is the board whose Small
#: State element 4 (index SS_ANGLE) carries the joint's angle.
Joint = collections.namedtuple('Joint', 'name board angle_unit has_spring')

ENCODER = 'as5055'      # 12-bit absolute magnetic encoder, 4096 counts/turn
ROTATION = 'rotation'   # incremental encoder of the rotational module

JOINTS = (
    Joint('camera_tilt', 20, ENCODER, False),
    Joint('front_tilt', 21, ENCODER, False),
    Joint('bend_i', 22, ENCODER, True),
    Joint('bend_ii', 23, ENCODER, True),
    Joint('rotation', 24, ROTATION, False),   # see ROTATION_BOARD
    Joint('bend_iii', 26, ENCODER, True),
    Joint('bend_iv', 27, ENCODER, True),
    Joint('rear_tilt', 28, ENCODER, False),
    # Camera pan has no angle in the Small State (Table B.1 gives board 20 a
    # single angle, the tilt); it is reconstructed from what board 20 is sent
    # (pirate.state.camera_pan).
    Joint('camera_pan', None, ENCODER, False),
)
JOINT_NAMES = tuple(j.name for j in JOINTS)
BEND_JOINTS = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')

# --- Small State layout (Table B.1) -----------------------------------------
# Zero-based indices into SmallState.data (the report numbers them from 1).
SS_ODOMETRY = 0      # wheel odometry, counts (int16, wraps)
SS_VELOCITY = 1      # wheel velocity, counts per 20 ms sample
SS_DRIVE_LOAD = 2    # drive motor duty, -256..256
SS_ANGLE = 3         # joint angle, counts (boards 20-24, 26-28; 25: rotation)
SS_BEND_LOAD = 4     # spring deflection, spring-encoder counts
SS_TORQUE = 5        # torque controller output, -256..256
SMALL_STATE_SIZE = 9
#: Added to a Small State's board by the Mega when that board did not answer
#: its request this cycle (the data are then 0): a board gone silent, told
#: apart from a reply lost on the way to the laptop.
NO_ANSWER = 0x80

#: Board 25 carries the IMU (SPEC 2 follows Table B.1, not Table 2.1's board
#: 24): gravity vector X, Y, Z and angular rates U, V, W in elements 4-9.
IMU_BOARD = 25
SS_IMU_X, SS_IMU_Y, SS_IMU_Z, SS_IMU_U, SS_IMU_V, SS_IMU_W = 3, 4, 5, 6, 7, 8
#: The rotation encoder sits on board 25, whose elements 4-9 are all taken by
#: the IMU (Table B.1). The Mega reports it in the angle element of board 24,
#: the other rotational-module board, which has no joint of its own.
ROTATION_BOARD = 24
#: Odometry and wheel speed: every drive board reports its own wheel (all six
#: share one setpoint); the state fuses them (pirate.state.odometry, median).
#: The three wheels of each part's V (front: Bend I, Bend II and the front
#: rotational module; rear: the rear rotational module, Bend III, Bend IV):
#: a part's own odometry, for a step that drives on one clamped part while
#: the other lies open on its shells (pirate.sequencer.pabs.turn_motions).
PART_WHEEL_BOARDS = {'front': (22, 23, 24), 'rear': (25, 26, 27)}
#: Boards whose readings the PABs use: front tilt (21), Bend I-IV angles and
#: odometry (22, 23, 26, 27), rotation (24), orientation (25). A silent camera
#: (20) or rear (28) board makes the state stale but stops no PAB.
PAB_BOARDS = (21, 22, 23, 24, 25, 26, 27)
