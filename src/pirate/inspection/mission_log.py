"""The timeline of a run, read for the report: pure.

Two JSON Lines files, one object per event: the recorder's
(pirate.inspection.store.TIMELINE_FILE: the missions as it heard them)
and the mission executive's log, in the run folder
(:data:`MISSION_LOG_FILE`) or given to the report. An event's time is its
first of :data:`TIME_KEYS` present, its words its first of
:data:`TEXT_KEYS` (else the whole object); anything else is shown as it is.
A run without a log has no timeline; a line that is not JSON is skipped
with a warning.
"""
import json
import os

MISSION_LOG_FILE = 'mission.jsonl'
TIME_KEYS = ('stamp_s', 'time_s', 't', 'time', 'stamp', 'wall_time')
TEXT_KEYS = ('text', 'message', 'event', 'line')
ALONG_KEYS = ('along_mm',)


def read_events(path):
    """([(time or None, text, along_mm or None)], warnings) of the log at
    ``path``; ([], []) when there is none."""
    if path is None or not os.path.exists(path):
        return [], []
    events, warnings = [], []
    with open(path, 'rb') as stream:
        for number, raw in enumerate(stream.read().decode('utf-8', 'replace').split('\n'), 1):
            if not raw.strip():
                continue
            try:
                entry = json.loads(raw)
            except ValueError as error:
                warnings.append('%s line %d: skipped, not JSON (%s)' % (path, number, error))
                continue
            events.append(_event(entry))
    return events, warnings


def _first(entry, keys):
    for key in keys:
        if key in entry:
            return entry[key]
    return None


def _event(entry):
    if not isinstance(entry, dict):
        return None, json.dumps(entry), None
    text = _first(entry, TEXT_KEYS)
    rest = {k: v for k, v in entry.items() if k not in TIME_KEYS + TEXT_KEYS + ALONG_KEYS}
    if text is None:
        text = json.dumps(rest, sort_keys=True)
    elif rest:
        text = '%s %s' % (text, json.dumps(rest, sort_keys=True))
    along = _first(entry, ALONG_KEYS)
    return _first(entry, TIME_KEYS), str(text), along if isinstance(along, (int, float)) else None
