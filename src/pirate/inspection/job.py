"""An inspection job: a route there and back and the findings to mark on it (pure).

A job file (config/jobs/inspection_demo.yaml) names the pipe map, the
route's points (visited in order, the first and the last the launch pit)
and the marks: each a kind (:data:`pirate.inspection.findings.KINDS`), the
operator's note, and where it is marked: when the mission's estimate of
the robot's middle first passes ``along_mm`` (mm along the map) on the
``leg`` named, ``in`` (before the route's farthest point) or ``back``.
And its inspection stops, due the same way (``along_mm``, ``leg``,
``note``): there the mission pauses (the robot stands), the front camera
looks each way of ``views_deg`` ([pan, tilt] pairs, degrees; default
ahead, left, right, up, down) and each view is recorded as a finding of
kind ``view`` (both cameras' frames; not in the dig list), the camera
turns back ahead and the mission resumes (:func:`run_stop`).
"""
import collections
import math

import yaml

from pirate.inspection import findings
from pirate.supervisory import planner

Job = collections.namedtuple('Job', 'map points marks stops')
Mark = collections.namedtuple('Mark', 'along_mm leg kind note')
#: An inspection stop: where it is due (as a mark) and the views, (pan, tilt) rad.
Stop = collections.namedtuple('Stop', 'along_mm leg note views')
LEGS = ('in', 'back')
#: An inspection stop's views when the job names none: ahead, the wall left
#: and right, the top and the bottom ((pan, tilt) degrees; the pan and tilt
#: reach +-86 deg in the twin, config/twin.yaml camera.range_rad).
DEFAULT_VIEWS_DEG = ((0, 0), (-60, 0), (60, 0), (0, 45), (0, -45))
#: Largest pan or tilt a view may ask, degrees: what the encoder tells (half a turn).
VIEW_MAX_DEG = 180
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
    unknown = set(data) - {'map', 'route', 'marks', 'stops'}
    if unknown:
        raise JobError('%s: unknown key(s) %s (map, route, marks, stops)' % (path, ', '.join(sorted(unknown))))
    return Job(data['map'], points, [_mark(path, k, entry) for k, entry in enumerate(data.get('marks') or [], 1)],
               [_stop(path, k, entry) for k, entry in enumerate(data.get('stops') or [], 1)])


def _mark(path, number, entry):
    where = '%s: mark %d' % (path, number)
    along, leg = _due_where(where, entry, Mark._fields)
    try:
        kind = findings.check_kind(entry.get('kind', 'other'))
    except findings.FindingError as error:
        raise JobError('%s: %s' % (where, error))
    return Mark(along, leg, kind, str(entry.get('note', '')))


def _stop(path, number, entry):
    where = '%s: stops, entry %d' % (path, number)
    fields = ('along_mm', 'leg', 'note', 'views_deg')
    along, leg = _due_where(where, entry, fields)
    views = entry.get('views_deg', DEFAULT_VIEWS_DEG)
    if not isinstance(views, (list, tuple)) or not views or not all(
            isinstance(v, (list, tuple)) and len(v) == 2 and all(_degrees(a) for a in v) for v in views):
        raise JobError('%s: views_deg must be [pan, tilt] pairs in degrees within +-%d, not %r'
                       % (where, VIEW_MAX_DEG, views))
    return Stop(along, leg, str(entry.get('note', '')),
                tuple((math.radians(pan), math.radians(tilt)) for pan, tilt in views))


def _degrees(value):
    return not isinstance(value, bool) and isinstance(value, (int, float)) and abs(value) <= VIEW_MAX_DEG


def _due_where(where, entry, fields):
    """(along_mm, leg) of a mark's or stop's ``entry``; JobError naming ``where``."""
    if not isinstance(entry, dict):
        raise JobError('%s: {%s}, not %r' % (where, ', '.join(fields), entry))
    unknown = set(entry) - set(fields)
    if unknown:
        raise JobError('%s: unknown key(s) %s (%s)' % (where, ', '.join(sorted(unknown)), ', '.join(fields)))
    along = entry.get('along_mm')
    if isinstance(along, bool) or not isinstance(along, (int, float)) or along < 0:
        raise JobError('%s: along_mm must be a distance in mm >= 0, not %r' % (where, along))
    if entry.get('leg', 'in') not in LEGS:
        raise JobError('%s: leg must be one of %s, not %r' % (where, ', '.join(LEGS), entry.get('leg')))
    return float(along), entry.get('leg', 'in')


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


def run_stop(stop, robot, say):
    """Make inspection stop ``stop`` with ``robot``, which answers
    ``pause()``, ``resume()``, ``point(pan_rad, tilt_rad)`` and
    ``mark(note)`` with (ok, message), and waits in ``stands()`` until the
    robot stands paused and in ``pointed(pan_rad, tilt_rad)`` until the
    camera reads there (True, or False when its wait ran out). Each view is
    marked (said when the camera was not there yet); the camera turns back
    ahead and the mission resumes whatever happened after the pause.
    ``say(line)`` prints. Returns the number of views marked."""
    ok, message = robot.pause()
    if not ok:
        say('stop at %.0f mm not made: %s' % (stop.along_mm, message))
        return 0
    marked = 0
    try:
        if not robot.stands():
            say('stop at %.0f mm: the robot did not come to rest; no views' % stop.along_mm)
            return 0
        turned = False
        for pan, tilt in stop.views:
            ok, message = robot.point(pan, tilt)
            if not ok:
                say('stop at %.0f mm: %s' % (stop.along_mm, message))
                break
            turned = True
            there = robot.pointed(pan, tilt)
            ok, message = robot.mark('%s (pan %+.0f deg, tilt %+.0f deg%s)' % (
                stop.note or 'inspection stop', math.degrees(pan), math.degrees(tilt),
                '' if there else '; the camera had not got there'))
            marked += ok
            say('view: %s' % message)
        if turned:
            robot.point(0.0, 0.0)
            robot.pointed(0.0, 0.0)
    finally:
        ok, message = robot.resume()
        say('stop at %.0f mm: %d of %d views; %s' % (stop.along_mm, marked, len(stop.views), message))
    return marked
