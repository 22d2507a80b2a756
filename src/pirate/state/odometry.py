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

Counts are in the robot's forward sense on every board (the twin, the
fake and the firmware-in-the-loop boards report them so; the mirrored
mounting of the apex modules, tables.WHEEL_SIGN, is undone before they
reach the laptop, as for the setpoints). Pure: no ROS.
"""
import statistics

from pirate.robot import tables, units


class WheelOdometry(object):
    """Fuses the drive boards' odometry counts into one travel, mm."""

    def __init__(self, boards=tables.DRIVE_BOARDS):
        self.boards = tuple(boards)
        self._last_raw = {}          # board -> last raw int16 count
        self._pending = {}           # board -> counts since the last fold
        self._counts = 0.0           # fused travel, counts

    def update(self, board, raw):
        """One drive board's raw (int16, wrapping) odometry count."""
        last = self._last_raw.get(board)
        self._last_raw[board] = raw
        if last is None:
            return                   # the board's first reading is its zero
        self._pending[board] = self._pending.get(board, 0) + units.unwrap_int16(last, raw)

    def fold(self):
        """End of a refresh cycle: add the median of the wheels' increments."""
        if self._pending:
            self._counts += statistics.median(self._pending.values())
        self._pending = {}

    @property
    def mm(self):
        """Fused travel since the first readings, mm (forward positive)."""
        return units.odometry_to_mm(self._counts)
