"""Where the robot is on the map: odometry, re-anchored at every junction.

Wheel odometry drifts (slip, the wheels' path round a bend is not the
pipe's axis), so the estimate is re-anchored where the map is certain: at
a junction a junction PAB has detected. A junction found where the map and
odometry do not put one (farther than the tolerance), or none found where
the map has one, means the map disagrees with the pipe: :class:`MapMismatch`,
and the mission stops safe.

Positions are metres along the map's path of the robot's middle (as in
pirate.supervisory.planner); odometry is the robot's wheel odometry in mm,
growing when it drives forward (it never turns round, so the way back is
negative odometry, SPEC 6). Pure: no ROS.
"""
import collections

from pirate.sequencer.junctions import is_turn

#: One junction's check: the junction, where odometry put the robot (m) and where the map does (m).
Fix = collections.namedtuple('Fix', 'junction estimated_m mapped_m')


class MapMismatch(RuntimeError):
    """The pipe is not what the map says."""


class Localiser(object):
    """Dead reckoning along the path, anchored at the start and at each junction found."""

    def __init__(self, start_m, settings):
        self.anchor_m, self.anchor_odometry = start_m, None
        self.along_m = start_m
        self.fixes = []
        self._robot = settings['robot']
        self._tolerance_m = settings['locate_tolerance_mm'] / 1000.0
        self._drift = settings['odometry_drift']

    def update(self, odometry_mm):
        """A new odometry reading: the estimate follows it from the anchor."""
        if self.anchor_odometry is None:
            self.anchor_odometry = odometry_mm
        self.along_m = self.estimate(odometry_mm)
        return self.along_m

    def estimate(self, odometry_mm):
        """Where ``odometry_mm`` puts the robot (m along), changing nothing:
        for showing the position live between the executive's updates."""
        if self.anchor_odometry is None:
            return self.anchor_m
        return self.anchor_m + (odometry_mm - self.anchor_odometry) / 1000.0

    def uncertainty_m(self, odometry_mm):
        """How far the robot may be from :meth:`estimate` (m): the bound
        within which the localiser takes a junction to be the map's, the
        tolerance plus the drift over the distance since the anchor."""
        return self._tolerance_m + self._drift * abs(self.estimate(odometry_mm) - self.anchor_m)

    def junction_found(self, junction, odometry_mm, sign):
        """A junction PAB detected ``junction`` (its leading V lost the wall)
        at ``odometry_mm`` (the robot's odometry then, not the PAB's
        distance from its start), driving forward (``sign`` 1) or back (-1).
        Re-anchor there, or raise :class:`MapMismatch`."""
        allowed = self.uncertainty_m(odometry_mm)
        estimated = self.update(odometry_mm)
        mapped = sensed_at_m(junction, sign, self._robot)
        if abs(estimated - mapped) > allowed:
            raise MapMismatch('%s found with the robot at %.0f mm, the map has it at %.0f mm '
                              '(more than %.0f mm apart)' % (junction.name, estimated * 1000, mapped * 1000,
                                                             allowed * 1000))
        self.fixes.append(Fix(junction.name, estimated, mapped))
        self.anchor_m, self.anchor_odometry, self.along_m = mapped, odometry_mm, mapped
        return mapped

    def turn_taken(self, end_m, odometry_mm):
        """A turn's PAB ended with the robot in the new pipe, its middle at
        ``end_m`` (the planner's ``turn_end_mm`` past the junction: where the
        turn's steps leave it, set by the robot's geometry). Re-anchor there:
        round the corner the wheels slip while the middle swings, clamped,
        and the odometry over-counts (about 250 mm per turn in the twin)."""
        self.anchor_m, self.anchor_odometry, self.along_m = end_m, odometry_mm, end_m

    @staticmethod
    def junction_missing(junction, searched_mm):
        """The map's junction was not found within the search distance."""
        return MapMismatch('%s not found within %.0f mm of where the map has it' % (junction.name, searched_mm))


def sensed_at_m(junction, sign, robot):
    """Where the robot's middle is (m along) when a junction PAB senses
    ``junction`` driving forward (``sign`` 1: the front V's apex reaches its
    entry, ``robot['sense_front_mm']`` ahead of the middle) or back (-1: the
    rear V's apex reaches its exit). A turn senses its junction differently
    (Bend II round the corner, the middle ``robot['sense_turn_mm']`` before
    the entry). ``robot``: config/supervisory.yaml's row."""
    if sign > 0:
        ahead_mm = robot['sense_turn_mm'] if is_turn(junction.direction) else robot['sense_front_mm']
        return junction.entry_m - ahead_mm / 1000.0
    return junction.exit_m + robot['sense_rear_mm'] / 1000.0
