"""A run's findings on disk, written so that nothing is lost if a node dies.

A run is a folder (default ``~/.ros/pirate/inspections/<run>/``)::

    run.json            the run: name, map, launch pit (written once)
    findings.jsonl      one finding per line, appended and fsynced as marked
    finding_001_front.png, finding_001_rear.png ...   the camera frames
    timeline.jsonl      the missions as the recorder heard them: goals, steps, results
    mission.jsonl       the mission executive's log, when it writes one there

A finding's frames are written (and fsynced) before its line, so a line
never names a frame that is not there. A node that dies mid-write leaves at
most a truncated last line: :func:`read_findings` skips it with a warning.
Pure: no ROS.
"""
import datetime
import io
import json
import os

FINDINGS_FILE = 'findings.jsonl'
TIMELINE_FILE = 'timeline.jsonl'
RUN_FILE = 'run.json'
#: The file in the runs folder naming the run a restarted node goes on with.
CURRENT_FILE = 'current'
DEFAULT_ROOT = os.path.join(os.path.expanduser('~'), '.ros', 'pirate', 'inspections')


class RunError(ValueError):
    """A run folder that cannot be read or written: says which and why."""


def _fsync_write(path, data, mode='wb'):
    with open(path, mode) as stream:
        stream.write(data)
        stream.flush()
        os.fsync(stream.fileno())


def new_run_name(now=None):
    """'run-20261127-181900' for ``now`` (a UTC datetime; default now)."""
    return (now or datetime.datetime.utcnow()).strftime('run-%Y%m%d-%H%M%S')


def current_run(root, new=False, now=None):
    """The run a recorder starts or goes on with under ``root``: the one
    named in ``root/current`` unless ``new`` or none is named; a new one
    (its folder made, so two started in the same second differ) is named
    there."""
    marker = os.path.join(root, CURRENT_FILE)
    if not new and os.path.isfile(marker):
        with open(marker) as stream:
            name = stream.read().strip()
        if name:
            return name
    name, taken = new_run_name(now), 1
    while os.path.exists(os.path.join(root, name if taken == 1 else '%s-%d' % (name, taken))):
        taken += 1
    name = name if taken == 1 else '%s-%d' % (name, taken)
    os.makedirs(os.path.join(root, name))
    _fsync_write(marker, (name + '\n').encode())
    return name


class RunStore(object):
    """One run's folder: append findings and their frames; read them back."""

    def __init__(self, folder, about=None):
        """Open (create) the run at ``folder``; ``about`` (dict: map,
        launch pit ...) is written to run.json the first time only."""
        self.folder = folder
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as error:
            raise RunError('%s: cannot make the run folder: %s' % (folder, error))
        if about is not None and not os.path.exists(os.path.join(folder, RUN_FILE)):
            write_about(folder, about)
        self.findings, self.warnings = read_findings(folder, missing_ok=True)
        self.missions = _timeline_missions(folder)

    def log_mission(self, event, mission_id):
        """Log a mission's ``event`` once per ``mission_id`` (its goal id) in
        this run, across restarts of the node."""
        if mission_id not in self.missions:
            self.log_event(dict(event, mission_id=mission_id))
            self.missions.add(mission_id)

    def next_number(self):
        """The number the next finding gets (1, 2, ...)."""
        return max([f['number'] for f in self.findings] or [0]) + 1

    def save_frame(self, number, camera, png_bytes):
        """Write one camera's frame of finding ``number``; its file name."""
        name = 'finding_%03d_%s.png' % (number, camera)
        _fsync_write(os.path.join(self.folder, name), png_bytes)
        return name

    def append(self, finding):
        """Append one finding (a JSON-able dict with a ``number``) as a line, fsynced."""
        _append_line(os.path.join(self.folder, FINDINGS_FILE), finding)
        self.findings.append(finding)
        return finding

    def log_event(self, event):
        """Append one event of the timeline (a JSON-able dict), fsynced."""
        _append_line(os.path.join(self.folder, TIMELINE_FILE), event)


def _timeline_missions(folder):
    """The goal ids of the missions the timeline of ``folder`` holds."""
    path = os.path.join(folder, TIMELINE_FILE)
    if not os.path.exists(path):
        return set()
    missions = set()
    with open(path, 'rb') as stream:
        for raw in stream.read().decode('utf-8', 'replace').split('\n'):
            try:
                event = json.loads(raw)
            except ValueError:          # blank, or cut short by a dead node
                continue
            if isinstance(event, dict) and event.get('mission_id'):
                missions.add(event['mission_id'])
    return missions


def _append_line(path, record):
    line = json.dumps(record, sort_keys=True) + '\n'
    if _ends_unterminated(path):      # a line cut short by a dead node: start a fresh line
        line = '\n' + line
    _fsync_write(path, line.encode(), mode='ab')


def _ends_unterminated(path):
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return False
    with open(path, 'rb') as stream:
        stream.seek(-1, io.SEEK_END)
        return stream.read(1) != b'\n'


def write_about(folder, about):
    """Write run.json of ``folder`` (whole or not at all: a new file renamed over the old)."""
    path = os.path.join(folder, RUN_FILE)
    _fsync_write(path + '.new', json.dumps(about, sort_keys=True).encode())
    os.replace(path + '.new', path)


def read_about(folder):
    """run.json of ``folder`` as a dict ({} when there is none)."""
    path = os.path.join(folder, RUN_FILE)
    if not os.path.exists(path):
        return {}
    try:
        with open(path) as stream:
            return json.load(stream)
    except ValueError as error:
        raise RunError('%s: not JSON: %s' % (path, error))


def read_findings(folder, missing_ok=False):
    """(findings in order, warnings) of the run at ``folder``.

    A line that is not a JSON object is skipped with a warning when it is
    the last one (a write cut short); anywhere else it is corruption:
    :class:`RunError` with the line's number. ``missing_ok``: a run with no
    findings file yet has none (else RunError)."""
    if not os.path.isdir(folder):
        raise RunError('%s: no such run folder' % folder)
    path = os.path.join(folder, FINDINGS_FILE)
    if not os.path.exists(path):
        if missing_ok:
            return [], []
        raise RunError('%s: no %s: nothing was marked in this run (or it is not a run folder)'
                       % (folder, FINDINGS_FILE))
    with open(path, 'rb') as stream:
        lines = stream.read().decode('utf-8', 'replace').split('\n')
    numbered = [(n + 1, text) for n, text in enumerate(lines) if text.strip()]
    findings, warnings = [], []
    for index, (number, text) in enumerate(numbered):
        try:
            finding = json.loads(text)
            if not isinstance(finding, dict) or 'number' not in finding or 'position' not in finding:
                raise ValueError('not a finding (a JSON object with number and position)')
        except ValueError as error:
            if index == len(numbered) - 1 or _cut_short(text, numbered, index):
                warnings.append('%s line %d: skipped, cut short (%s)' % (path, number, error))
                continue
            raise RunError('%s line %d: corrupt: %s' % (path, number, error))
        findings.append(finding)
    return findings, warnings


def _cut_short(text, numbered, index):
    """A line that a later append started fresh after: a JSON object's
    beginning whose end is missing (the node died writing it)."""
    return text.lstrip().startswith('{') and not text.rstrip().endswith('}') and index < len(numbered) - 1
