"""Pirate State: raw Small State messages -> the robot's state in SI units.

The blackboard of report 4.8.2: keeps the newest value of every sensor and
hands out a consistent snapshot on request. Pure Python; the caller passes
the (monotonic) time of arrival, so staleness is testable and does not stop
when a simulated clock stops.

Bad input rule (one place): a Small State from an unknown board, of the
wrong length, or with any element outside what its sensor can produce
(angle, rotation, wheel speed, drive duty, gravity) is dropped whole, with a
reason the node logs once; the previous values stay.

Freshness per board: the Mega skips a board that does not
answer, so the newest message of *any* board says nothing about board 22.
Every board's last arrival is kept; one silent for ``stale_after`` (or never
heard while others are) makes the whole state stale, naming it in
``Snapshot.silent``. :func:`pab_blocker` says whether that stops the PABs:
a silent board they read does (the clamp angles come from boards 22, 23, 26,
27); a silent camera or rear board does not. Odometry and wheel speed are
the median of the six drive boards (:mod:`pirate.state.odometry`), so one
wheel off the wall or one dead encoder does not become the robot's travel.
"""
import collections
import math
import statistics

from pirate.robot import tables, units
from pirate.state.camera_pan import PanEstimate, drive_config
from pirate.state.odometry import WheelOdometry

#: Newest data older than this (s, monotonic) makes the state stale: three
#: Mega cycles of 0.1 s missed; measurements.md#silent-board.
STALE_AFTER_S = 0.3
#: Largest joint angle an AS5055 reports (half a turn either way).
ANGLE_MAX_COUNTS = 2048
#: An accelerometer reading (all three axes) this far from 1 g is not gravity.
GRAVITY_TOLERANCE = 0.5
#: The roll about the robot's axis is read from gravity's (y, z) part only
#: while that part holds this much of 1 g (pitched at most 60 deg): pitched
#: steeper, as in a pipe going up or down, the roll is not defined and the
#: last one read is held (the rotation encoder still tells the parts apart).
ROLL_MIN_G = 0.5
#: Largest rotation reading, rad: half a turn either way. The safety limit
#: is +-0.7 rad (pirate.robot.safety); a reading beyond half a turn is a
#: broken sensor or a corrupted message, never the module.
ROTATION_READING_MAX_RAD = math.pi
#: Largest wheel speed a board can report: twice the robot's maximum.
WHEEL_READING_MAX_MM_S = 2 * 170.0
#: Drive duty and torque controller output, counts (the PICO's range).
DUTY_READING_MAX = 256

Snapshot = collections.namedtuple(
    'Snapshot', 'name position effort orientation odometry velocity stale age silent part_odometry')


class BadState(ValueError):
    """A Small State that was dropped, with the reason."""


class StateAssembler(object):
    """Accumulates Small States; answers snapshots in SI units."""

    def __init__(self, stale_after=STALE_AFTER_S, pan=None):
        self.stale_after = stale_after
        self.pan = pan or PanEstimate(*drive_config())     # the camera pan: no encoder
        self._raw = {}                  # board -> list of 9 ints
        self._arrival = {}              # board -> monotonic time
        self._odometry = WheelOdometry()
        self._orientation = math.pi / 2
        self._previous_board = None

    def update(self, board, data, now):
        """Take one Small State; return True when a refresh cycle is complete.

        Raises :class:`BadState` (and keeps the old values) for bad input.
        """
        data = list(data)
        _check(board, data)
        if board == tables.IMU_BOARD:
            self._orientation = _orientation(data, self._orientation)
        new_cycle = self._previous_board is not None and board <= self._previous_board
        if new_cycle:
            self._odometry.fold()       # the last cycle missed board 28
        if board in tables.DRIVE_BOARDS:
            self._odometry.update(board, data[tables.SS_ODOMETRY])
        self._raw[board] = data
        self._arrival[board] = now
        complete = board == tables.BOARDS[-1] or new_cycle
        if board == tables.BOARDS[-1]:
            self._odometry.fold()
        self._previous_board = board
        return complete

    def command(self, setpoints, modes, now):
        """The setpoint and control arrays sent to the robot at ``now`` (the
        camera pan's angle is reconstructed from them, :mod:`camera_pan`)."""
        self.pan.command(list(setpoints), list(modes), now)

    def age(self, now):
        """Seconds since the newest Small State (inf if none yet)."""
        return now - max(self._arrival.values()) if self._arrival else float('inf')

    def silent(self, now):
        """Boards not heard for ``stale_after`` s (or never), once any board was."""
        if not self._arrival:
            return ()
        return tuple(b for b in tables.BOARDS
                     if now - self._arrival.get(b, -math.inf) > self.stale_after)

    def snapshot(self, now):
        """The robot's state now, as a :data:`Snapshot` (rad, mNm, mm, mm/s)."""
        positions, efforts = [], []
        for joint in tables.JOINTS:
            raw = self._raw.get(joint.board)
            positions.append(self.pan.angle(now) if joint.board is None else _joint_angle(joint, raw))
            efforts.append(units.spring_to_mnm(raw[tables.SS_BEND_LOAD])
                           if raw is not None and joint.has_spring else 0.0)
        speeds = [self._raw[b][tables.SS_VELOCITY] for b in tables.DRIVE_BOARDS if b in self._raw]
        velocity = units.wheel_counts_to_mm_s(statistics.median(speeds)) if speeds else 0.0
        age = self.age(now)
        silent = self.silent(now)
        return Snapshot(list(tables.JOINT_NAMES), positions, efforts, self._orientation,
                        self._odometry.mm, velocity,
                        age > self.stale_after or bool(silent), age, silent,
                        {part: self._odometry.part_mm(part) for part in tables.PART_WHEEL_BOARDS})


def pab_blocker(stale, silent, age):
    """Why a state cannot steer a PAB, or None.

    A state is unusable when it is stale because of a board the PABs read
    (tables.PAB_BOARDS) or because nothing arrives at all; a silent camera or
    rear board alone stops no PAB.
    """
    if not stale:
        return None
    blocking = tuple(b for b in silent if b in tables.PAB_BOARDS)
    if silent and not blocking:
        return None
    return stale_reason(blocking or silent, age)


def stale_reason(silent, age):
    """Why a state is stale, naming the silent boards."""
    if silent and len(silent) < len(tables.BOARDS):
        return 'board%s %s silent' % ('s' if len(silent) > 1 else '', ', '.join(str(b) for b in silent))
    return 'no Small State for %.2f s' % age


def _check(board, data):
    if board not in tables.BOARDS:
        raise BadState('Small State from unknown board %r (boards are %d-%d); dropped'
                       % (board, tables.BOARDS[0], tables.BOARDS[-1]))
    if len(data) != tables.SMALL_STATE_SIZE:
        raise BadState('Small State of board %d has %d elements, not %d; dropped'
                       % (board, len(data), tables.SMALL_STATE_SIZE))
    if board == tables.IMU_BOARD:
        g = math.sqrt(sum(data[i] ** 2 for i in (tables.SS_IMU_X, tables.SS_IMU_Y, tables.SS_IMU_Z)))
        g /= units.IMU_COUNTS_PER_G
        if abs(g - 1.0) > GRAVITY_TOLERANCE:
            raise BadState('IMU of board %d reads %.2f g, not gravity; dropped' % (board, g))
    else:
        _check_angle(board, data[tables.SS_ANGLE])
    if board in tables.DRIVE_BOARDS:
        speed = units.wheel_counts_to_mm_s(data[tables.SS_VELOCITY])
        if abs(speed) > WHEEL_READING_MAX_MM_S:
            raise BadState('wheel speed %.0f mm/s of board %d is beyond +-%.0f mm/s; dropped'
                           % (speed, board, WHEEL_READING_MAX_MM_S))
    duty_elements = (tables.SS_DRIVE_LOAD,) if board == tables.IMU_BOARD else (tables.SS_DRIVE_LOAD, tables.SS_TORQUE)
    duty = [data[i] for i in duty_elements]
    if any(abs(d) > DUTY_READING_MAX for d in duty):
        raise BadState('drive/torque duty %s of board %d is beyond +-%d; dropped'
                       % (duty, board, DUTY_READING_MAX))


def _check_angle(board, counts):
    """The angle element against what its sensor can produce."""
    joint = next((j for j in tables.JOINTS if j.board == board), None)
    if joint is None:
        return
    if joint.angle_unit == tables.ENCODER and abs(counts) > ANGLE_MAX_COUNTS:
        raise BadState('angle %d counts of board %d is beyond an AS5055 (+-%d); dropped'
                       % (counts, board, ANGLE_MAX_COUNTS))
    if joint.angle_unit == tables.ROTATION and abs(units.rotation_to_rad(counts)) > ROTATION_READING_MAX_RAD:
        raise BadState('rotation %d counts (%.2f rad) of board %d is beyond +-%.2f rad; dropped'
                       % (counts, units.rotation_to_rad(counts), board, ROTATION_READING_MAX_RAD))


def _orientation(data, last_roll):
    """The roll from gravity's (y, z) part, or ``last_roll`` when the robot is
    pitched too steeply for that part to define one (:data:`ROLL_MIN_G`)."""
    g_y, g_z = data[tables.SS_IMU_Y], data[tables.SS_IMU_Z]
    if math.hypot(g_y, g_z) < ROLL_MIN_G * units.IMU_COUNTS_PER_G:
        return last_roll
    return units.gravity_to_roll(g_y, g_z)


def _joint_angle(joint, raw):
    if raw is None:
        return 0.0
    counts = raw[tables.SS_ANGLE]
    if joint.angle_unit == tables.ROTATION:
        return units.rotation_to_rad(counts)
    return units.encoder_to_rad(counts)
