"""Missions are checked before anything moves.

Each case is a mission text and the words its error must carry, with the
line number; the shipped missions pass; the runner prints the trace from
the result, not from feedback.
"""
import glob
import os
import subprocess
import sys

import pytest

from pirate import paths
from pirate.supervisory.mission import (MissionError, MissionRunner, TracedPrimitive, load_mission,
                                        parse_mission, plan)

GOOD = """\
name: t
pipe_diameter: 90
steps:
  - {pab: CLAMP_STRAIGHT}
  - {pab: DRIVE, distance: 50, speed: 150}
  - {pab: drive, distance: -30}
  - {pab: HOME, pipe_diameter: 110}
"""

BAD = {   # mission text: words the error must contain
    'key typo': ("steps:\n  - {pab: CLAMP_STRAIGHT}\n  - {pab: DRIVE, distnace: 50}\n",
                 ['line 3', "unknown key 'distnace'", 'needs a distance']),
    'speed too high': ("steps:\n  - {pab: CLAMP_STRAIGHT}\n  - {pab: DRIVE, distance: 5, speed: 1000}\n",
                       ['line 3', 'speed 1000', '170']),
    'yaml syntax': ("steps:\n  - {pab: HOME\n  - {pab: DRIVE}\n", ['line 3', 'YAML syntax']),
    'unknown pab': ("steps:\n  - {pab: FLY}\n", ['line 2', "unknown PAB 'FLY'", 'HOME']),
    'not built': ("steps:\n  - {pab: MITRE_BEND, option: DOWN}\n", ['line 2', 'not implemented']),
    'option missing': ("steps:\n  - {pab: MITRE_BEND}\n", ['line 2', 'needs an option', 'LEFT / RIGHT']),
    'option not allowed': ("steps:\n  - {pab: HOME, option: LEFT}\n", ['line 2', "option 'LEFT'", 'none']),
    'distance on clamp': ("steps:\n  - {pab: CLAMP_STRAIGHT, distance: 5}\n", ['line 2', 'takes no distance']),
    'diameter': ("pipe_diameter: 100\nsteps:\n  - {pab: HOME}\n", ['line 1', '100 mm', '90, 110']),
    'diameter type': ("steps:\n  - {pab: HOME, pipe_diameter: abc}\n", ['line 2', 'integer', 'abc']),
    'distance type': ("steps:\n  - {pab: DRIVE, distance: '50'}\n", ['line 2', 'number']),
    'distance zero': ("steps:\n  - {pab: DRIVE, distance: 0}\n", ['line 2', 'distance 0']),
    'distance inf': ("steps:\n  - {pab: DRIVE, distance: .inf}\n", ['line 2', 'finite']),
    'top key': ("stpes:\n  - {pab: HOME}\n", ['line 1', "unknown key 'stpes'", 'no steps']),
    'no steps': ("name: x\n", ['no steps']),
    'empty': ("", ['empty']),
    'step not a mapping': ("steps:\n  - HOME\n", ['line 2', 'mapping']),
}


def test_a_good_mission_and_its_plan():
    mission = parse_mission(GOOD)
    assert [(s.pab, s.pipe_diameter, s.distance, s.speed) for s in mission.steps] == [
        ('CLAMP_STRAIGHT', 90, 0.0, 0.0), ('DRIVE', 90, 50.0, 150.0), ('DRIVE', 90, -30.0, 0.0),
        ('HOME', 110, 0.0, 0.0)]
    lines = plan(mission, 150.0)
    assert lines[0].startswith('mission: t (4 PABs)')
    assert lines[3] == '[3] DRIVE -30 mm at 150 mm/s, 90 mm pipe'


@pytest.mark.parametrize('case', sorted(BAD))
def test_bad_missions_are_refused_with_the_line(case):
    text, words = BAD[case]
    with pytest.raises(MissionError) as error:
        parse_mission(text)
    for word in words:
        assert word in str(error.value), (case, str(error.value))


def test_every_error_at_once():
    text = "steps:\n  - {pab: DRIVE, distnace: 5}\n  - {pab: FLY}\n"
    with pytest.raises(MissionError) as error:
        parse_mission(text)
    assert str(error.value).count('line ') == 3


@pytest.mark.parametrize('path', sorted(glob.glob(os.path.join(paths.CONFIG_DIR, 'missions', '*.yaml'))))
def test_shipped_missions_are_valid(path):
    assert load_mission(path).steps


def test_check_prints_the_plan_without_ros(tmp_path):
    node = os.path.join(paths.PACKAGE_DIR, 'nodes', 'run_mission')
    out = subprocess.run([sys.executable, node, '--check'], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert '[2] DRIVE +50 mm at 150 mm/s, 90 mm pipe' in out.stdout
    bad = tmp_path / 'bad.yaml'
    bad.write_text(BAD['key typo'][0])
    out = subprocess.run([sys.executable, node, '--check', str(bad)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 2 and "line 3: unknown key 'distnace'" in out.stderr
    assert 'Traceback' not in out.stderr


def test_runner_prints_the_trace_from_the_result():
    mission = parse_mission(GOOD)
    trace = [TracedPrimitive('move front', 'front_tilt >= 0.400', 1.0, 3.9, 'reached'),
             TracedPrimitive('clamp rear', 'bend_iv <= -0.77', 3.9, 7.0, 'reached')]
    lines = []
    calls = []

    def run_goal(step):
        calls.append(step.pab)
        return ('succeeded', 'ok', trace) if len(calls) == 1 else ('aborted', 'stuck', trace[:1])
    results = MissionRunner(run_goal, lambda: (0.0, 0.0), out=lines.append).run(mission)
    assert calls == ['CLAMP_STRAIGHT', 'DRIVE']          # stops at the first failure
    assert [r.primitives for r in results] == [['move front', 'clamp rear'], ['move front']]
    assert any('clamp rear' in line and '3.9 ->' in line and 'reached' in line for line in lines)
    assert 'FAILED' in lines[-1] and '3 motion primitives' in lines[-1]
