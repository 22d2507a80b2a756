"""The robot's odometry: the median of its six wheels, cycle by cycle.

Every drive board reports its own wheel's encoder (Table B.1, element 1;
boards 22-27). One wheel alone is not the robot's travel: a wheel that
loses the wall (the front module's shell propping Bend I's wheel up, an
apex wheel over a T-joint's hole, a partly unclamped V) spins free at the
commanded speed and counts travel that did not happen; a slipping wheel
does the same. The report (7.2) recommends fusing sensors. Here each Mega
refresh cycle adds the median of the wheels' increments in that cycle:
while at most two of the six wheels misbehave the median is a wheel that
rolls on the wall, and a dead or silent encoder only drops out of the vote
(a board that did not report in the cycle does not vote).

A cycle is folded only when most drive boards (:data:`MIN_VOTES` of six)
have reported since the last fold; otherwise their increments wait for
the next fold. A fold with a few boards would count their cycle a second
time when the others' replies of the same cycle are folded later (replies
of one cycle split over two folds by loss, delay or reordering each give
the cycle's travel as their median).

Three wheels spinning free outvote nothing: lying on its side with one V
open, that part rests on its shells and its three wheels all count the
setpoint (twin: measurements.md#twin-odometry). So
each part's three wheels are also fused on their own, the same way
(:meth:`WheelOdometry.part_mm`): a step that drives on one clamped part
reads that part's travel.

Counts are in the robot's forward sense on every board (the twin, the
fake and the firmware-in-the-loop boards report them so; the mirrored
mounting of the apex modules, tables.WHEEL_SIGN, is undone before they
reach the laptop, as for the setpoints). Pure: no ROS.
"""
import statistics

from pirate.robot import tables, units

#: Drive boards that must have reported for a fold: a majority of the six
#: (measurements.md#lossy-bus-odometry).
MIN_VOTES = 4


class _Fused(object):
    """One group of wheels: per cycle, the median of their increments, counts."""

    def __init__(self, boards):
        self.boards = frozenset(boards)
        self.counts = 0.0

    def fold(self, pending):
        votes = [counts for board, counts in pending.items() if board in self.boards]
        if votes:
            self.counts += statistics.median(votes)


class WheelOdometry(object):
    """Fuses the drive boards' odometry counts into one travel, mm, and one per part."""

    def __init__(self, boards=tables.DRIVE_BOARDS, parts=tables.PART_WHEEL_BOARDS):
        self.boards = tuple(boards)
        self._last_raw = {}          # board -> last raw int16 count
        self._pending = {}           # board -> counts since the last fold
        self._robot = _Fused(self.boards)
        self._parts = {part: _Fused(wheels) for part, wheels in parts.items()}

    def update(self, board, raw):
        """One drive board's raw (int16, wrapping) odometry count."""
        last = self._last_raw.get(board)
        self._last_raw[board] = raw
        if last is None:
            return                   # the board's first reading is its zero
        self._pending[board] = self._pending.get(board, 0) + units.unwrap_int16(last, raw)

    def fold(self):
        """End of a refresh cycle: add the median of the wheels' increments,
        when :data:`MIN_VOTES` boards have reported (else they wait); True when folded."""
        if len(self._pending) < MIN_VOTES:
            return False
        for fused in (self._robot,) + tuple(self._parts.values()):
            fused.fold(self._pending)
        self._pending = {}
        return True

    @property
    def mm(self):
        """Fused travel since the first readings, mm (forward positive)."""
        return units.odometry_to_mm(self._robot.counts)

    def part_mm(self, part):
        """``part``'s ('front' / 'rear') three wheels fused alike, mm since the first readings."""
        return units.odometry_to_mm(self._parts[part].counts)
