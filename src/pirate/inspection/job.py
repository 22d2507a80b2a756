"""An inspection job: a route there and back and the findings to mark on it (pure).

A job file (config/jobs/inspection_demo.yaml) names the pipe map, the
route's points (visited in order, the first and the last the launch pit)
and the marks: each a kind (:data:`pirate.inspection.findings.KINDS`), the
operator's note, and where it is marked: when the mission's estimate of
the robot's middle first passes ``along_mm`` (mm along the map) on the
``leg`` named, ``in`` (before the route's farthest point) or ``back``.
"""
import collections

import yaml

from pirate.inspection import findings
from pirate.supervisory import planner

Job = collections.namedtuple('Job', 'map points marks')
Mark = collections.namedtuple('Mark', 'along_mm leg kind note')
LEGS = ('in', 'back')
#: The junction PABs: round a corner their estimate is odometry, not yet re-anchored.
JUNCTION_PABS = ('MITRE_BEND', 'T_JOINT')


class JobError(ValueError):
    """A job file that cannot be run: says what is wrong."""


def load(path):
    """The :data:`Job` in the YAML file ``path``; :class:`JobError` naming what is wrong."""
    try:
        with open(path) as stream:
            data = yaml.safe_load(stream)
    except (IOError, OSError, yaml.YAMLError) as error:
        raise JobError('%s: %s' % (path, error))
    if not isinstance(data, dict) or not isinstance(data.get('map'), str):
        raise JobError('%s: a job names its map (map: NAME)' % path)
    points = data.get('route')
    if not isinstance(points, list) or len(points) < 2 or not all(isinstance(p, str) for p in points):
        raise JobError('%s: route: the names of two points or more, in order' % path)
    return Job(data['map'], points, [_mark(path, k, entry) for k, entry in enumerate(data.get('marks') or [], 1)])


def _mark(path, number, entry):
    where = '%s: mark %d' % (path, number)
    if not isinstance(entry, dict):
        raise JobError('%s: {along_mm, leg, kind, note}, not %r' % (where, entry))
    unknown = set(entry) - set(Mark._fields)
    if unknown:
        raise JobError('%s: unknown key(s) %s (along_mm, leg, kind, note)' % (where, ', '.join(sorted(unknown))))
    along = entry.get('along_mm')
    if isinstance(along, bool) or not isinstance(along, (int, float)) or along < 0:
        raise JobError('%s: along_mm must be a distance in mm >= 0, not %r' % (where, along))
    if entry.get('leg', 'in') not in LEGS:
        raise JobError('%s: leg must be one of %s, not %r' % (where, ', '.join(LEGS), entry.get('leg')))
    try:
        kind = findings.check_kind(entry.get('kind', 'other'))
    except findings.FindingError as error:
        raise JobError('%s: %s' % (where, error))
    return Mark(float(along), entry.get('leg', 'in'), kind, str(entry.get('note', '')))


def corners_mm(pipe_map):
    """(entry, exit) mm along ``pipe_map`` of each junction a route turns at
    (a bend, a T-joint's branch): round one the estimate runs ahead."""
    return [(junction.entry_m * 1000.0, junction.exit_m * 1000.0)
            for junction in planner.junctions(pipe_map) if planner.turns(junction)]


def due_marks(marks, pipe_map, robot):
    """:class:`DueMarks` for ``marks`` on ``pipe_map``, held from when the
    leading wheel of ``robot`` (config/supervisory.yaml: ``front_mm`` and
    ``rear_mm`` from the middle) reaches a corner."""
    return DueMarks(marks, corners_mm(pipe_map), max(robot['front_mm'], robot['rear_mm']))


class DueMarks(object):
    """Which marks are due as the mission goes: a mark is due once, when
    the estimate passes its ``along_mm`` (either way, a re-anchoring jump
    included) on its leg; the leg is ``back`` from the first step the
    robot takes rear first (a negative distance) on. While a junction PAB
    takes a corner no mark falls due: from when the estimate comes within
    ``reach_mm`` (the robot's leading wheel reaching it) of one of
    ``corners`` (:func:`corners_mm`) to the PAB's end, its wheels' odometry
    runs ahead of the robot's middle round the corner until the turn's end
    re-anchors the estimate (measurements.md#round-trip-mark-error); a mark
    it passed then falls due once the estimate has passed it after. Before
    the corner, and through a T-joint straight on, the estimate is the
    straight pipe's and marks fall due as they are passed."""

    def __init__(self, marks, corners=(), reach_mm=0.0):
        self._left = list(marks)
        self._corners = [(entry - reach_mm, exit_ + reach_mm) for entry, exit_ in corners]
        self._last = None
        self._step = None
        self._junction_pab = False
        self._holding = False
        self.leg = 'in'

    def step(self, distance_mm, pab='', number=None):
        """The mission's running step (``number``) is PAB ``pab`` with the signed distance ``distance_mm``."""
        if distance_mm < 0:
            self.leg = 'back'
        if (number, pab, distance_mm) != self._step:
            self._step = (number, pab, distance_mm)
            self._junction_pab = pab in JUNCTION_PABS
            self._holding = False

    def passed(self, along_mm):
        """The marks due now the estimate is at ``along_mm``, in the order passed."""
        if self._junction_pab and not self._holding:
            self._holding = any(low <= along_mm <= high for low, high in self._corners)
        if self._holding:
            return []
        last = along_mm if self._last is None else self._last
        self._last = along_mm
        low, high = min(last, along_mm), max(last, along_mm)
        due = [m for m in self._left if m.leg == self.leg and low <= m.along_mm <= high]
        self._left = [m for m in self._left if m not in due]
        return sorted(due, key=lambda m: m.along_mm, reverse=along_mm < last)

    def left(self):
        """The marks not yet due."""
        return list(self._left)
