"""Missions: a list of PAB goals run one after the other (report 5.12).

The Supervisory layer's first brick: each goal is sent, waited for, and the
mission stops at the first goal that does not succeed. A mission file is
checked completely before anything moves: unknown keys, types,
ranges, PAB names and their options, pipe diameters without guards - each
error with its line number, all of them at once. Pure Python; the action
client and the printer are passed in (nodes/run_mission wires them).
"""
import collections
import math

import yaml

from pirate.robot import safety
from pirate.sequencer.pabs import drive
from pirate.sequencer.goals import CODES as _CODES, OPTION_NAMES, OPTIONS, PAB_FIELDS, PAB_OPTIONS, built

Step = collections.namedtuple('Step', 'pab code pipe_diameter distance speed option')
Mission = collections.namedtuple('Mission', 'name steps')
StepResult = collections.namedtuple('StepResult', 'step status message robot_s wall_s primitives')
#: One line of a goal's trace as the result carries it (robot times, s).
TracedPrimitive = collections.namedtuple('TracedPrimitive', 'name guard start end outcome')

_INT, _FLOAT = 'tag:yaml.org,2002:int', 'tag:yaml.org,2002:float'
MISSION_KEYS = ('name', 'pipe_diameter', 'steps')
STEP_KEYS = ('pab', 'pipe_diameter', 'distance', 'speed', 'option')


class MissionError(ValueError):
    """A mission file that cannot be run; the message lists every problem by line."""


class _Checker(object):
    """Collects every problem of one mission file, each with its line."""

    def __init__(self, diameters, drive):
        self.diameters = tuple(diameters)
        self.drive = drive
        self.errors = []

    def error(self, node, text):
        self.errors.append('line %d: %s' % (node.start_mark.line + 1, text))

    def mapping(self, node, keys, what):
        """{key: value node} of a YAML mapping; unknown keys reported."""
        if not isinstance(node, yaml.MappingNode):
            self.error(node, '%s must be a mapping (key: value)' % what)
            return {}
        found = {}
        for key_node, value_node in node.value:
            key = key_node.value
            if key not in keys:
                self.error(key_node, 'unknown key %r in %s (known: %s)' % (key, what, ', '.join(keys)))
            elif key in found:
                self.error(key_node, 'key %r twice in %s' % (key, what))
            else:
                found[key] = value_node
        return found

    def number(self, node, what, kind=float):
        """The scalar ``node`` as ``kind``; None (and an error) when it is not one."""
        tags = (_INT,) if kind is int else (_INT, _FLOAT)
        try:
            if not isinstance(node, yaml.ScalarNode) or node.tag not in tags:
                raise ValueError
            value = kind(yaml.safe_load(node.value))
            if not math.isfinite(value):
                raise ValueError
            return value
        except (TypeError, ValueError, yaml.YAMLError):
            self.error(node, '%s must be a finite %s, not %r' % (
                what, 'integer' if kind is int else 'number', getattr(node, 'value', node)))
            return None

    def diameter(self, node, default):
        if node is None:
            return default
        mm = self.number(node, 'pipe_diameter', int)
        if mm is not None and mm not in self.diameters:
            self.error(node, 'no guards for a %d mm pipe (configured: %s mm)'
                       % (mm, ', '.join(str(d) for d in self.diameters)))
        return mm

    def step(self, number, node, default_mm):
        what = 'step %d' % number
        fields = self.mapping(node, STEP_KEYS, what)
        if not fields:
            return None
        if 'pab' not in fields:
            self.error(node, '%s has no pab (known: %s)' % (what, ', '.join(sorted(_CODES))))
            return None
        pab = str(fields['pab'].value).upper()
        if pab not in _CODES:
            self.error(fields['pab'], '%s: unknown PAB %r (known: %s)' % (what, fields['pab'].value,
                                                                          ', '.join(sorted(_CODES))))
            return None
        if not built(pab):
            self.error(fields['pab'], '%s: PAB %s is not implemented yet' % (what, pab))
        for key in ('distance', 'speed'):
            if key in fields and key not in PAB_FIELDS.get(pab, ()):
                self.error(fields[key], '%s: %s takes no %s' % (what, pab, key))
        mm = self.diameter(fields.get('pipe_diameter'), default_mm)
        option = self.option(what, pab, fields.get('option'), node)
        if option != OPTIONS['NONE'] and built(pab) and not built(pab, OPTION_NAMES[option]):
            self.error(fields['option'], '%s: PAB %s %s is not implemented yet' % (what, pab, OPTION_NAMES[option]))
        distance = speed = 0.0
        if pab == 'DRIVE':
            distance, speed = self.drive_fields(what, fields, node)
        return Step(pab, _CODES[pab], mm, distance, speed, option)

    def option(self, what, pab, node, step_node):
        allowed = PAB_OPTIONS.get(pab, ())
        if node is None:
            if allowed:
                self.error(step_node, '%s: %s needs an option (%s)' % (what, pab, ' / '.join(allowed)))
            return OPTIONS['NONE']
        name = str(node.value).upper()
        if name not in allowed:
            self.error(node, '%s: option %r for %s (allowed: %s)'
                       % (what, node.value, pab, ' / '.join(allowed) or 'none'))
            return OPTIONS['NONE']
        return OPTIONS[name]

    def drive_fields(self, what, fields, node):
        if 'distance' not in fields:
            self.error(node, '%s: DRIVE needs a distance (mm, signed)' % what)
            distance = None
        else:
            distance = self.number(fields['distance'], 'distance (mm)')
        problem = distance is not None and drive.distance_problem(distance, float(self.drive['max_distance']))
        if problem:
            self.error(fields['distance'], '%s: %s' % (what, problem))
        speed = 0.0
        if 'speed' in fields:
            speed = self.number(fields['speed'], 'speed (mm/s)')
            if speed is not None and not 0 < speed <= safety.DRIVE_MAX_MM_S:
                self.error(fields['speed'], '%s: speed %g mm/s outside (0, %g] mm/s'
                           % (what, speed, safety.DRIVE_MAX_MM_S))
        return distance or 0.0, speed or 0.0


def parse_mission(text, diameters=(90, 110), drive=None):
    """A checked :data:`Mission` from YAML text (see config/missions/).

    ``diameters``: pipe diameters that have guards; ``drive``: the drive
    settings of config/sequencer.yaml (``max_distance``). Raises
    :class:`MissionError` listing every problem with its line number.
    """
    checker = _Checker(diameters, drive or {'max_distance': 5000.0})
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as bad:
        mark = getattr(bad, 'problem_mark', None)
        where = 'line %d: ' % (mark.line + 1) if mark is not None else ''
        raise MissionError('%sYAML syntax error: %s' % (where, getattr(bad, 'problem', None) or bad))
    if root is None:
        raise MissionError('mission is empty')
    top = checker.mapping(root, MISSION_KEYS, 'the mission')
    default_mm = checker.diameter(top.get('pipe_diameter'), 90)
    steps = []
    steps_node = top.get('steps')
    if not isinstance(steps_node, yaml.SequenceNode) or not steps_node.value:
        checker.error(steps_node or root, 'mission has no steps (a list under "steps:")')
    else:
        for number, node in enumerate(steps_node.value, 1):
            steps.append(checker.step(number, node, default_mm))
    if checker.errors:
        raise MissionError('\n'.join(checker.errors))
    name = top['name'].value if 'name' in top else 'mission'
    return Mission(str(name), steps)


def load_mission(path, diameters=(90, 110), drive=None):
    """Read and check a mission file."""
    with open(path) as stream:
        return parse_mission(stream.read(), diameters, drive)


def plan(mission, default_speed):
    """The mission as lines of text, for ``run_mission --check``; nothing moves."""
    lines = ['mission: %s (%d PABs), checked' % (mission.name, len(mission.steps))]
    for number, step in enumerate(mission.steps, 1):
        lines.append('[%d] %s' % (number, describe(step, default_speed)))
    return lines


def describe(step, default_speed=None):
    """One step in words: PAB, distance and speed, option, pipe."""
    text = step.pab
    if step.pab == 'DRIVE':
        speed = step.speed or default_speed
        text += ' %+.0f mm at %s mm/s' % (step.distance, '%.0f' % speed if speed else 'the default')
    if step.option:
        text += ' %s' % OPTION_NAMES[step.option]
    return '%s, %d mm pipe' % (text, step.pipe_diameter)


class MissionRunner(object):
    """Runs a mission through ``run_goal(step) -> (status, message, trace)``.

    ``trace`` is the result's list of :data:`TracedPrimitive` (robot times),
    so what is printed is what ran, whatever feedback was lost.
    ``clocks()`` returns (robot time s, wall time s) so durations are given
    in both; ``out`` prints a line.
    """

    def __init__(self, run_goal, clocks, out=print):
        self._run_goal = run_goal
        self._clocks = clocks
        self._out = out

    def run(self, mission):
        """Run every step until one fails; return the list of StepResults."""
        results = []
        self._out('mission: %s (%d PABs)' % (mission.name, len(mission.steps)))
        robot0, wall0 = self._clocks()
        for number, step in enumerate(mission.steps, 1):
            results.append(self._run_step(number, step))
            if results[-1].status != 'succeeded':
                self._out('mission stopped at step %d: %s' % (number, results[-1].message))
                break
        robot1, wall1 = self._clocks()
        ok = len(results) == len(mission.steps) and results[-1].status == 'succeeded'
        self._out('mission %s: %s in %.1f s robot time (%.1f s wall), %d motion primitives'
                  % (mission.name, 'SUCCEEDED' if ok else 'FAILED', robot1 - robot0, wall1 - wall0,
                     sum(len(r.primitives) for r in results)))
        return results

    def _run_step(self, number, step):
        self._out('[%d] %s' % (number, describe(step)))
        robot0, wall0 = self._clocks()
        status, message, trace = self._run_goal(step)
        robot1, wall1 = self._clocks()
        for prim in trace:
            self._out('      %-26s %6.1f -> %6.1f s  %4.1f s  %s (%s)'
                      % (prim.name, prim.start - robot0, prim.end - robot0, prim.end - prim.start,
                         prim.outcome, prim.guard))
        self._out('    %s %s: %s (%.1f s robot time, %.1f s wall)'
                  % (step.pab, status, message, robot1 - robot0, wall1 - wall0))
        return StepResult(step, status, message, robot1 - robot0, wall1 - wall0,
                          [prim.name for prim in trace])
