"""The repository speaks of the product, and its figures have their rows.

Every tracked file (code, config, tests, launch, firmware, docs) says what
the product is and why, not when or in which piece of work it was made: no
issue number, no work period, no merged branch, no pointer into a
development diary. History lives in git. Each failure lists file:line.

A measured figure points to its row of doc/measurements.md
(``measurements.md#row``): every such pointer must name a row that exists,
and every row's command must be a bench script with options it has.
"""
import os
import re
import subprocess

import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
MEASUREMENTS = os.path.join(ROOT, 'doc', 'measurements.md')
THIS_FILE = os.path.relpath(os.path.abspath(__file__), ROOT)

_UNITS = r'(?:mm|ms|s|rad|deg|counts|mNm|N|%|Hz)\b'
#: (pattern, what it names): words that date a text instead of describing the product.
HISTORY = [
    (re.compile(r'\bissues?[ \t]*[-#]?[ \t]*\d+', re.I), 'an issue number'),
    (re.compile(r'(?<![\w#&/])#\d+\.\d+\b'), 'an issue number'),
    (re.compile(r'\bnotes/'), 'the development notes'),
    (re.compile(r'\b[Ss]top \d+\b(?![.\d])(?![ \t]*' + _UNITS + ')'), 'a work period'),
    (re.compile(r'\b(?:[Tt]his|[Ll]ast|[Pp]revious) stop\b(?! bit)'), 'a work period'),
    (re.compile(r'(?<![A-Za-z])(?:stop|issue)_?\d+'), 'a work period in a name'),
    (re.compile(r'\b(?:twin[2-9]|clamp2|turns2|super2|turnspeed|turnresume|teebranch)\b'), 'a merged branch'),
    (re.compile(r'\bbranch(?:es)? [`\'"]\w+[`\'"]'), 'a merged branch'),
    (re.compile(r'\bhelpers? [`\'"]\w+[`\'"]'), 'a helper of the work'),
]
POINTER = re.compile(r'measurements\.md#([A-Za-z0-9_-]+)')
ROW_ID = re.compile(r'<a id="([A-Za-z0-9_-]+)"></a>')
BENCH_COMMAND = re.compile(r'python3 bench/([A-Za-z0-9_]+)([^`]*)`')
OPTION = re.compile(r'(?<![\w-])(--[a-z][a-z0-9-]*)')


def tracked_files():
    """Paths (relative to the package) git tracks; every file under it without git."""
    try:
        out = subprocess.check_output(['git', 'ls-files', '-z'], cwd=ROOT, stderr=subprocess.DEVNULL)
        return sorted(p for p in out.decode('utf-8').split('\0') if p)
    except (OSError, subprocess.CalledProcessError):
        found = []
        for top, dirs, files in os.walk(ROOT):
            dirs[:] = [d for d in dirs if not d.startswith('.')]
            found.extend(os.path.relpath(os.path.join(top, f), ROOT) for f in files)
        return sorted(found)


def text_lines(path):
    """The lines of a text file, or [] for a binary (or missing) one."""
    try:
        with open(os.path.join(ROOT, path), 'rb') as f:
            data = f.read()
    except (IOError, OSError):
        return []
    if b'\0' in data:
        return []
    try:
        return data.decode('utf-8').splitlines()
    except UnicodeDecodeError:
        return []


def history_words(line):
    """What in ``line`` dates it rather than describes the product ([] if nothing)."""
    return ['%s (%r)' % (what, m.group(0)) for pattern, what in HISTORY for m in pattern.finditer(line)]


def history_hits(paths):
    return ['%s:%d: %s' % (path, number, ', '.join(words))
            for path in paths if path != THIS_FILE
            for number, line in enumerate(text_lines(path), 1)
            for words in [history_words(line)] if words]


def measurement_rows():
    with open(MEASUREMENTS) as f:
        return ROW_ID.findall(f.read())


def pointers(paths):
    """(file:line, row) of every measurements.md#row in ``paths``."""
    return [('%s:%d' % (path, number), row)
            for path in paths if path != THIS_FILE
            for number, line in enumerate(text_lines(path), 1)
            for row in POINTER.findall(line)]


@pytest.mark.parametrize('line', [
    '"""Sensing a junction (report 4.7.4; issue 10.5)."""',
    'a rogue is refused (issue #14.7)',
    '- #14.3: control modes restored',
    '# see notes/issue-10.md',
    'Waiting in the press (2 s of ROS time, stop 29) was',
    "'before stop 29': _before_stop_29,",
    'def _before_stop_29(root):',
    'def test_issue10_livelock():',
    'measured in this stop',
    '(notes of the lead, after stop 22)',
    "Merge branch 'twin3' into main",
    '(branch twin5)',
    'Issue 11 point 6. The executive',
    '# --- issue 13: every PAB from the panel ---',
])
def test_the_history_words_are_found(line):
    assert history_words(line)


@pytest.mark.parametrize('line', [
    'close_window_mm: 15.0      # measurements.md#junction-sensing-window',
    'the lift guard stops 0.03 rad short',
    'wait for the last stop bit before releasing the bus',
    'an emergency stop 2 s after the press',
    'the front stops 40 mm before the hole',
    'Table 6.4 / report 5.12: clamp, drive',
    'Issue a Stop, then Home',
    'a T-joint entered through its branch turns left',
    '#!/usr/bin/env python3',
    'boards that stop answering (the Mega skips them)',
    'So Play after Stop never moves a joint by itself',
    '| STOP 8 | every board stops |',
    "COMMAND_CODES = {'stop': 8, 'single_stop': 9}",
    'colour: "#14a3ff"',
])
def test_product_words_are_not_history(line):
    assert history_words(line) == []


def test_no_tracked_file_names_an_issue_a_work_period_a_branch_or_the_notes():
    hits = history_hits(tracked_files())
    assert hits == [], 'the product must speak of the product (%d lines):\n%s' % (len(hits), '\n'.join(hits))


def test_every_measurement_row_is_named_once():
    rows = measurement_rows()
    assert rows, 'doc/measurements.md has no rows'
    twice = sorted({row for row in rows if rows.count(row) > 1})
    assert twice == []


def test_every_measurements_pointer_names_a_row():
    rows = set(measurement_rows())
    found = pointers(tracked_files())
    assert found, 'no file points into doc/measurements.md'
    missing = ['%s: measurements.md#%s' % (where, row) for where, row in found if row not in rows]
    assert missing == [], 'pointers to rows doc/measurements.md does not have:\n' + '\n'.join(missing)


def test_a_pointer_to_a_missing_row_is_found():
    rows = set(measurement_rows())
    assert 'no-such-row' not in rows
    assert POINTER.findall('x: 1  # why; measurements.md#no-such-row') == ['no-such-row']


def bench_commands():
    """(bench script, its options) of every command doc/measurements.md gives."""
    with open(MEASUREMENTS) as f:
        return [(name, OPTION.findall(rest)) for name, rest in BENCH_COMMAND.findall(f.read())]


#: The options every bench that runs through the sweep runner takes, and a sweep of drawn robots.
SWEEP_OPTIONS = {'sweep_cli.add_arguments': os.path.join(ROOT, 'src', 'pirate', 'sweep', 'cli.py'),
                 'drawn_robots.add_arguments': os.path.join(ROOT, 'src', 'pirate', 'testing', 'drawn_robots.py')}


def bench_source(path):
    """A bench's text, with the shared options it takes (the sweep runner's, drawn robots')."""
    with open(path) as f:
        source = f.read()
    for call, module in SWEEP_OPTIONS.items():
        if call in source:
            with open(module) as f:
                source += f.read()
    return source


def test_every_measurement_command_is_a_bench_script_with_those_options():
    commands = bench_commands()
    assert commands, 'doc/measurements.md names no bench command'
    wrong = []
    for name, options in commands:
        path = os.path.join(ROOT, 'bench', name)
        if not os.path.isfile(path):
            wrong.append('bench/%s does not exist' % name)
            continue
        source = bench_source(path)
        wrong.extend('bench/%s has no option %s' % (name, option) for option in options
                     if "'%s'" % option not in source)
    assert wrong == [], '\n'.join(wrong)
