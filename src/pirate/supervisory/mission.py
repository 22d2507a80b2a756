"""Missions: a list of PAB goals run one after the other (report 5.12).

The Supervisory layer's first brick: each goal is sent, waited for, and the
mission stops at the first goal that does not succeed. Pure Python; the
action client and the printer are passed in (nodes/run_mission wires them).
"""
import collections

import yaml

from pirate.sequencer.pabs import PABS

Step = collections.namedtuple('Step', 'pab code pipe_diameter distance speed option')
Mission = collections.namedtuple('Mission', 'name steps')
StepResult = collections.namedtuple('StepResult', 'step status message robot_s wall_s primitives')

_CODES = {row[0]: code for code, row in PABS.items()}


class MissionError(ValueError):
    """A mission file that cannot be run, with the reason."""


def parse_mission(text):
    """A :data:`Mission` from YAML text (see config/missions/)."""
    data = yaml.safe_load(text) or {}
    steps = []
    for number, raw in enumerate(data.get('steps') or [], 1):
        pab = str(raw.get('pab', '')).upper()
        if pab not in _CODES:
            raise MissionError('step %d: unknown PAB %r (known: %s)' % (number, pab, ', '.join(sorted(_CODES))))
        steps.append(Step(pab, _CODES[pab], int(raw.get('pipe_diameter', data.get('pipe_diameter', 90))),
                          float(raw.get('distance', 0.0)), float(raw.get('speed', 0.0)),
                          int(raw.get('option', 0))))
    if not steps:
        raise MissionError('mission has no steps')
    return Mission(data.get('name', 'mission'), steps)


def load_mission(path):
    """Read and parse a mission file."""
    with open(path) as stream:
        return parse_mission(stream.read())


class MissionRunner(object):
    """Runs a mission through ``run_goal(step, on_feedback) -> (status, message)``.

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
        detail = ' %+.0f mm at %.0f mm/s' % (step.distance, step.speed) if step.pab == 'DRIVE' else ''
        self._out('[%d] %s%s, %d mm pipe' % (number, step.pab, detail, step.pipe_diameter))
        primitives = []
        running = {'name': '', 'since': 0.0}

        def on_feedback(primitive, guard):
            """Print a primitive's start and end from the feedback stream."""
            if primitive == running['name']:
                return
            robot_now = self._clocks()[0]
            if running['name']:
                self._out('      end   %-26s %.1f s' % (running['name'], robot_now - running['since']))
            if primitive:
                primitives.append(primitive)
                self._out('      start %-26s until %s' % (primitive, guard))
            running.update(name=primitive, since=robot_now)

        robot0, wall0 = self._clocks()
        status, message = self._run_goal(step, on_feedback)
        robot1, wall1 = self._clocks()
        self._out('    %s %s: %s (%.1f s robot time, %.1f s wall)'
                  % (step.pab, status, message, robot1 - robot0, wall1 - wall0))
        return StepResult(step, status, message, robot1 - robot0, wall1 - wall0, primitives)
