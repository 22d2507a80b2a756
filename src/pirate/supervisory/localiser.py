"""Where the robot is on the map: odometry, re-anchored at every junction.

Wheel odometry drifts (slip, the wheels' path round a bend is not the
pipe's axis), so the estimate is re-anchored where the map is certain: at
a junction a junction PAB has detected. A junction found where the map and
odometry do not put one (farther than the tolerance), or none found where
the map has one, means the map disagrees with the pipe: :class:`MapMismatch`,
and the mission stops safe. The same tolerance bounds the search: a
junction PAB looks only as far as a junction sensed there would still be
the map's (:meth:`Localiser.search`), so a junction further on than the map
says is not taken for it.

Positions are metres along the map's path of the robot's middle (as in
pirate.supervisory.planner); odometry is the robot's wheel odometry in mm,
growing when it drives forward (it never turns round, so the way back is
negative odometry, SPEC 6). Pure: no ROS.
"""
import collections

from pirate.sequencer.junctions import is_turn

#: One junction's check: the junction, where odometry put the robot (m) and where the map does (m).
Fix = collections.namedtuple('Fix', 'junction estimated_m mapped_m')
#: Where a junction PAB looks for the map's ``junction`` driving ``sign`` (1
#: forward, -1 back): where the map has it (``expected_m``: the robot's
#: middle when it senses it), from the estimate where the search starts to
#: the farthest it may go (``from_m``, ``to_m``), and how far the estimate
#: may be off there (``uncertainty_m``); all m along the map.
Search = collections.namedtuple('Search', 'junction sign expected_m from_m to_m uncertainty_m')


class MapMismatch(RuntimeError):
    """The pipe is not what the map says."""


class Localiser(object):
    """Dead reckoning along the path, anchored at the start and at each junction found."""

    def __init__(self, start_m, settings):
        self.anchor_m, self.anchor_odometry = start_m, None
        self.along_m, self.odometry_mm = start_m, None
        self.fixes = []
        self._robot = settings['robot']
        self._tolerance_m = settings['locate_tolerance_mm'] / 1000.0
        self._drift = settings['odometry_drift']
        self._slip = settings['steer_slip']
        self._slip_from = None      # (junction name, estimate m) where a search allowing slip began

    def update(self, odometry_mm):
        """A new odometry reading: the estimate follows it from the anchor."""
        if self.anchor_odometry is None:
            self.anchor_odometry = odometry_mm
        self.along_m, self.odometry_mm = self.estimate(odometry_mm), odometry_mm
        return self.along_m

    def state(self):
        """What restores this localiser (:func:`restored`), as plain data in
        mm: the estimate, its uncertainty, the last anchor (where on the map
        and the odometry there), the odometry of the estimate (None before
        the first reading) and the junctions found (by name, in order)."""
        return {'along_mm': round(self.along_m * 1000.0, 1), 'anchor_mm': round(self.anchor_m * 1000.0, 1),
                'anchor_odometry_mm': self.anchor_odometry, 'odometry_mm': self.odometry_mm,
                'found': [fix.junction for fix in self.fixes],
                'uncertainty_mm': round(self._uncertainty_at(self.along_m) * 1000.0, 1)}

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
        return self._uncertainty_at(self.estimate(odometry_mm))

    def _uncertainty_at(self, along_m):
        """:meth:`uncertainty_m` with the estimate at ``along_m`` (m along)."""
        return self._tolerance_m + self._drift * abs(along_m - self.anchor_m)

    def search(self, junction, sign, limit_mm):
        """The :data:`Search` for ``junction`` from the estimate now, driving
        ``sign``: as far as a junction sensed there would still be the map's
        (:meth:`junction_found`: the map's place plus the uncertainty there),
        at most ``limit_mm`` of odometry; nothing (``to_m`` = ``from_m``)
        when the estimate is already beyond it."""
        expected = sensed_at_m(junction, sign, self._robot)
        slip = self._slip_of(junction)
        self._slip_from = (junction.name, self.along_m) if slip else None
        reach_m = min(max(self._reach_m(expected, sign, slip), 0.0), limit_mm / 1000.0)
        to_m = self.along_m + sign * reach_m
        return Search(junction, sign, expected, self.along_m, to_m, self._uncertainty_at(to_m) + slip * reach_m)

    def _slip_of(self, junction):
        """The share of odometry a search for ``junction`` may count in slip:
        ``steer_slip`` for a turn at a junction already found, else 0."""
        found = any(fix.junction == junction.name for fix in self.fixes)
        return self._slip if found and is_turn(junction.direction) else 0.0

    def _reach_m(self, expected_m, sign, slip=0.0):
        """How far (m) the estimate may go ``sign``-wards before a junction
        sensed there lies farther than :meth:`uncertainty_m` (plus ``slip``
        of the way searched) beyond ``expected_m``: the root of d - ahead =
        tolerance + drift |beyond + d| + slip d (``ahead``: expected beyond
        the estimate, ``beyond``: the estimate beyond the anchor, both the
        way it drives), one per side of the anchor."""
        ahead, beyond = sign * (expected_m - self.along_m), sign * (self.along_m - self.anchor_m)
        past_anchor = (self._tolerance_m + ahead + self._drift * beyond) / (1.0 - self._drift - slip)
        if beyond + past_anchor >= 0.0:
            return past_anchor
        return (self._tolerance_m + ahead - self._drift * beyond) / (1.0 + self._drift - slip)

    def junction_found(self, junction, odometry_mm, sign):
        """A junction PAB detected ``junction`` (its leading V lost the wall)
        at ``odometry_mm`` (the robot's odometry then, not the PAB's
        distance from its start), driving forward (``sign`` 1) or back (-1).
        Re-anchor there, or raise :class:`MapMismatch`."""
        allowed = self.uncertainty_m(odometry_mm)
        estimated = self.update(odometry_mm)
        mapped = sensed_at_m(junction, sign, self._robot)
        if self._slip_from is not None and self._slip_from[0] == junction.name and sign * (estimated - mapped) > 0:
            allowed += self._slip * abs(estimated - self._slip_from[1])     # ahead: the steering's slip
        self._slip_from = None
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
        self.anchor_m, self.anchor_odometry, self.along_m, self.odometry_mm = end_m, odometry_mm, end_m, odometry_mm

    @staticmethod
    def junction_missing(search):
        """The map's junction was not found where :data:`Search` ``search`` looked."""
        junction, sign = search.junction, search.sign
        return MapMismatch('%s not found within %.0f mm: the map has it at %.0f mm (the robot\'s middle at %.0f mm '
                           'when it senses it); searched from %.0f to %.0f mm along the map, the estimate within '
                           '%.0f mm there'
                           % (junction.name, searched_mm(search), (junction.entry_m if sign > 0 else junction.exit_m)
                              * 1000, search.expected_m * 1000, search.from_m * 1000, search.to_m * 1000,
                              search.uncertainty_m * 1000))


def restored(state, settings):
    """A :class:`Localiser` from its :meth:`Localiser.state`: anchored where
    it was, so a later odometry reading moves the estimate on from there and
    the uncertainty grows with the distance since the anchor, and the
    junctions it had found found again (where, it does not keep). KeyError,
    TypeError or ValueError when ``state`` is not one."""
    localiser = Localiser(float(state['anchor_mm']) / 1000.0, settings)
    localiser.fixes = [Fix(str(name), None, None) for name in state.get('found', ())]
    odometry_mm, anchor_odometry = state['odometry_mm'], state['anchor_odometry_mm']
    if anchor_odometry is not None:
        localiser.anchor_odometry = float(anchor_odometry)
        localiser.update(float(odometry_mm))
    return localiser


def searched_mm(search):
    """How far (mm of odometry) :data:`Search` ``search`` lets the junction PAB drive."""
    return abs(search.to_m - search.from_m) * 1000.0


def sensed_at_m(junction, sign, robot):
    """Where the robot's middle is (m along) when a junction PAB senses
    ``junction`` driving forward (``sign`` 1: the front V's apex reaches its
    entry, ``robot['sense_front_mm']`` ahead of the middle) or back (-1: the
    rear V's apex reaches its exit, ``robot['sense_rear_mm']`` behind it).
    A turn senses its junction differently, either way: its leading V round
    the corner, the middle ``robot['sense_turn_mm']`` before the edge it
    meets (the entry forward, the exit back). ``robot``: config/supervisory.yaml's row."""
    edge_m = junction.entry_m if sign > 0 else junction.exit_m
    if is_turn(junction.direction):
        ahead_mm = robot['sense_turn_mm']
    else:
        ahead_mm = robot['sense_front_mm'] if sign > 0 else robot['sense_rear_mm']
    return edge_m - sign * ahead_mm / 1000.0
