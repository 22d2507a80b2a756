"""Pirate State: raw Small State messages -> the robot's state in SI units.

The blackboard of report 4.8.2: keeps the newest value of every sensor and
hands out a consistent snapshot on request. Pure Python; the caller passes
the (monotonic) time of arrival, so staleness is testable and does not stop
when a simulated clock stops.

Bad input rule (one place): a Small State from an unknown board, of the
wrong length, or with any element outside what its sensor can produce
(angle, rotation, wheel speed, drive duty, gravity) is dropped whole, with a
reason the node logs once; the previous values stay.

Freshness per board: the newest message of *any* board says nothing about
board 22. A board is silent when its replies stop, not when one or two are
lost (:class:`ReplyHistory`): ``stale_after`` without a reply once the Mega
said the board did not answer it (a Small State with :data:`tables.NO_ANSWER`
added to the board, data 0), whatever the link loses; without that word,
``stale_after`` on a clean link and on a lossy one as many missed cycles as
its own loss rate makes unlikely. A silent board (or one never heard while others are) makes the
whole state stale, naming it in ``Snapshot.silent``. :func:`pab_blocker` says whether that stops the PABs:
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
#: The Mega's refresh cycle (s) until replies have shown the real one.
CYCLE_S = 0.1
#: Mega cycles without a fold (board 28 lost or silent) after which the
#: odometry folds at a drive board's reply instead.
FOLD_OVERDUE_CYCLES = 2.5
#: Replies per board the loss rate and the cycle are judged over (10 s).
HISTORY_REPLIES = 100
#: Chance a board that merely loses replies is taken for silent, per cycle:
#: 1e-6 x 7 boards x 10 cycles/s is one false abort in 4 robot-hours.
FALSE_SILENCE = 1e-6
#: Most missed cycles a silence ever waits for (at a loss rate of 10 %, 6).
MAX_MISSED_CYCLES = 8
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
    'Snapshot', 'name position effort orientation odometry velocity stale age silent part_odometry missed')


class BadState(ValueError):
    """A Small State that was dropped, with the reason."""


class StateAssembler(object):
    """Accumulates Small States; answers snapshots in SI units."""

    def __init__(self, stale_after=STALE_AFTER_S, pan=None):
        self.stale_after = stale_after
        self.pan = pan or PanEstimate(*drive_config())     # the camera pan: no encoder
        self._raw = {}                  # board -> list of 9 ints
        self._arrival = {}              # board -> monotonic time
        self._replies = ReplyHistory(stale_after)
        self._odometry = WheelOdometry()
        self._orientation = math.pi / 2
        self._previous_board = None
        self._folded_at = None          # when the wheels' increments were last folded (or the first reply came)

    def update(self, board, data, now):
        """Take one Small State; return True when a refresh cycle is complete.

        Raises :class:`BadState` (and keeps the old values) for bad input.
        """
        data = list(data)
        if board & tables.NO_ANSWER and (board & ~tables.NO_ANSWER) in tables.BOARDS:
            board &= ~tables.NO_ANSWER          # the Mega: it did not answer; its values stay the last heard
            self._replies.no_answer(board, now)
            self._fold_odometry(board, now)
            return self._takes_its_place(board)
        _check(board, data)
        if board == tables.IMU_BOARD:
            self._orientation = _orientation(data, self._orientation)
        if board in tables.DRIVE_BOARDS:
            self._odometry.update(board, data[tables.SS_ODOMETRY])
        self._raw[board] = data
        self._replies.reply(board, now)
        self._arrival[board] = now
        self._fold_odometry(board, now)
        return self._takes_its_place(board)

    def _takes_its_place(self, board):
        """Board ``board`` was heard of in the cycle: True when that completes
        one. One state per cycle: at board 28, or (28 lost) when the next
        cycle starts."""
        new_cycle = self._previous_board is not None and board <= self._previous_board
        complete = board == tables.BOARDS[-1] or (new_cycle and self._previous_board != tables.BOARDS[-1])
        self._previous_board = board
        return complete

    def _fold_odometry(self, board, now):
        """Fold the wheels' increments at the end of a cycle (board 28), or,
        while board 28 is not heard, once a fold is :data:`FOLD_OVERDUE_CYCLES` late."""
        last = tables.BOARDS[-1]
        if self._folded_at is None:
            self._folded_at = now
        overdue = now - self._folded_at > FOLD_OVERDUE_CYCLES * self._replies.cycle()
        if (board == last or (overdue and board in tables.DRIVE_BOARDS)) and self._odometry.fold():
            self._folded_at = now

    def command(self, setpoints, modes, now):
        """The setpoint and control arrays sent to the robot at ``now`` (the
        camera pan's angle is reconstructed from them, :mod:`camera_pan`)."""
        self.pan.command(list(setpoints), list(modes), now)

    def age(self, now):
        """Seconds since the newest Small State (inf if none yet)."""
        return now - max(self._arrival.values()) if self._arrival else float('inf')

    def silent(self, now):
        """Boards whose replies stopped (:class:`ReplyHistory`), once any board was heard."""
        return self._replies.silent(now)

    def loss(self):
        """Board -> fraction of its recent replies lost (diagnostics)."""
        return {board: self._replies.loss(board) for board in tables.BOARDS}

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
                        {part: self._odometry.part_mm(part) for part in tables.PART_WHEEL_BOARDS},
                        tuple(b for b in self._replies.missed(now) if b not in silent))


class ReplyHistory(object):
    """When a board's replies have stopped, told from replies merely lost.

    Each reply's gap since the board's previous one, in Mega cycles (the
    cycle is the median gap observed, :data:`CYCLE_S` before any), says how
    many replies were missed in between; over the last
    :data:`HISTORY_REPLIES` that gives the board's loss rate ``r``. A board
    is silent once it missed ``k`` expected replies in a row, ``k`` the
    fewest with ``r ** k <= FALSE_SILENCE`` but at least ``stale_after``'s
    worth (3 cycles: a clean bus notices a silent board 0.3 s after its
    first missing reply, as before), plus half a cycle and the largest
    arrival jitter seen. At 10 % loss ``k`` is 6 (8 with 0-80 ms jitter,
    which reads as some loss): a silent board is noticed 0.6-0.9 s after its
    first missing reply instead of aborting a goal about once per Clamp
    Straight on three lost replies in a row (7 boards x 10 cycles/s x 1e-3);
    measurements.md#lossy-bus. The Mega's word that the board did not answer
    it makes the silence the board's, not the link's: silent once it said
    so for the fewest cycles in a row (3), or once ``k`` is the fewest again
    and passed whatever the loss (measurements.md#lossy-bus-silent).
    """

    def __init__(self, stale_after=STALE_AFTER_S):
        self.stale_after = stale_after
        self._last = {}                 # board -> time of its newest reply
        self._unanswered = {}           # board -> cycles the Mega said it did not answer since its newest reply
        self._first = None              # time of the first reply of any board
        self._missed = {}               # board -> deque of replies missed before each reply
        self._jitter = {}               # board -> deque of |gap - whole cycles| s
        self._gaps = collections.deque(maxlen=HISTORY_REPLIES)
        self._cycle = CYCLE_S

    def reply(self, board, now):
        """Board ``board`` answered at ``now`` (s, monotonic)."""
        if self._first is None:
            self._first = now
        unanswered = self._unanswered.pop(board, 0)
        last = self._last.get(board)
        self._last[board] = now
        if last is None:
            return
        gap = now - last
        if gap > 0:                     # none: the clock did not move (a simulated one, lagging), no cycle
            self._gaps.append(gap)
        if len(self._gaps) >= 10:
            self._cycle = statistics.median(self._gaps)
        cycles = max(1, int(round(gap / self._cycle)))
        if cycles > MAX_MISSED_CYCLES + 1:
            return                      # a silence that ended (a reset, a reconnect), not loss
        self._missed.setdefault(board, collections.deque(maxlen=HISTORY_REPLIES)).append(
            max(0, cycles - 1 - unanswered))    # the link's losses: not what the board did not answer
        self._jitter.setdefault(board, collections.deque(maxlen=HISTORY_REPLIES)).append(
            abs(gap - cycles * self._cycle))

    def no_answer(self, board, now):
        """The Mega says board ``board`` did not answer it (at ``now``, s): its
        silence is its own, not the link's loss."""
        if self._first is None:
            self._first = now
        self._unanswered[board] = self._unanswered.get(board, 0) + 1

    def cycle(self):
        """The Mega's refresh cycle as the replies show it (s)."""
        return self._cycle

    def loss(self, board):
        """Fraction of the board's recent replies lost (0 before any history)."""
        return _lost_fraction(self._missed.get(board, ()))

    def bus_loss(self):
        """Fraction of every board's recent replies lost: what a board's own
        few replies cannot tell yet (the first seconds) the bus's many do."""
        return _lost_fraction([m for missed in self._missed.values() for m in missed])

    def missed_cycles_allowed(self, board, bus_loss=None):
        """Replies in a row the board may miss before it is silent (the
        fewest once the Mega said it did not answer)."""
        least = self._least_missed()
        rate = max(self.loss(board), self.bus_loss() if bus_loss is None else bus_loss)
        if rate <= 0.0 or board in self._unanswered:
            return least
        if rate >= 1.0:
            return MAX_MISSED_CYCLES
        return min(MAX_MISSED_CYCLES, max(least, int(math.ceil(math.log(FALSE_SILENCE) / math.log(rate)))))

    def _least_missed(self):
        """Cycles in a row a board that answers nothing is silent after (3)."""
        return int(round(self.stale_after / self._cycle))

    def silence_after(self, board, bus_loss=None):
        """Seconds after its newest reply that the board counts as silent."""
        jitter = max(self._jitter.get(board, ()) or (0.0,))
        return (self.missed_cycles_allowed(board, bus_loss) + 0.5) * self._cycle + min(jitter, self._cycle)

    def missed(self, now):
        """Boards whose latest reply is missing (the Mega said so, or half a
        cycle and the jitter seen past when it was due): their values are the
        last ones heard."""
        if self._first is None:
            return ()
        return tuple(b for b in tables.BOARDS if b in self._unanswered or now - self._last.get(b, self._first)
                     > 1.5 * self._cycle + min(max(self._jitter.get(b, ()) or (0.0,)), self._cycle))

    def silent(self, now):
        """Boards whose replies stopped (or never came while others did): the
        Mega said the board did not answer the fewest cycles in a row, or the
        cycles it may miss passed without a reply."""
        if self._first is None:
            return ()
        bus_loss, least = self.bus_loss(), self._least_missed()
        return tuple(b for b in tables.BOARDS if self._unanswered.get(b, 0) >= least
                     or now - self._last.get(b, self._first) > self.silence_after(b, bus_loss))


def _lost_fraction(missed):
    """Replies lost / replies expected, from the misses before each reply."""
    lost = sum(missed)
    return lost / float(lost + len(missed)) if lost else 0.0


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
