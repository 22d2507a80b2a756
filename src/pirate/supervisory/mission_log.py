"""The mission executive's log on disk, written as it goes.

One JSON object per line (JSON Lines), appended and flushed per event, so
an executive killed mid-mission (SIGKILL, a crash, a laptop that lost
power a moment after) leaves everything it had said; a restarted one reads
how the last mission ended, or where it stood when the executive died.
Records: ``{"event": "start", "mission": ..., "steps": n, "goal": {map,
points, speed, no_home, level, policy}, "first_step": k, "localiser":
{...}}``, ``{"event": "step", "step": k, "pab": ..., "localiser": {...}}``
when step k starts and ``{"event": "step_end", ..., "status":
"succeeded"}`` when it succeeds (the localiser's state then:
pirate.supervisory.localiser ``state``), ``{"event": "say", "step": k,
"text": ...}`` (every line the executive says, k from 1), ``{"event":
"end", "status": ..., "message": ...}``; each with ``"t"``, the wall time
(s since the epoch). pirate.supervisory.resume takes an interrupted
mission up from them. Pure file I/O: no ROS.
"""
import collections
import json
import os
import time

#: How the last mission in a log ended: ``status`` as the executive's
#: Outcome (succeeded, aborted, ...) or ``interrupted`` when the log stops
#: before its end (the executive died); ``message`` says it in words.
Ending = collections.namedtuple('Ending', 'mission status message step steps')


class MissionLog(object):
    """Appends records to ``path`` (its folder made if missing), one flushed line each."""

    def __init__(self, path, clock=time.time):
        folder = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(folder):
            os.makedirs(folder)
        self.path, self._clock = path, clock
        self._file = open(path, 'a')

    def write(self, record):
        """Append ``record`` (a dict) as one line, flushed to the file now."""
        line = dict(record, t=round(self._clock(), 3))
        self._file.write(json.dumps(line, sort_keys=True) + '\n')
        self._file.flush()

    def close(self):
        self._file.close()


def read(path):
    """The records of the log at ``path`` ([] when there is none); a last
    line cut short by a death mid-write is left out."""
    if not os.path.exists(path):
        return []
    records = []
    with open(path) as log:
        for line in log:
            try:
                records.append(json.loads(line))
            except ValueError:
                continue
    return records


def last_ending(records):
    """How the last mission of ``records`` ended (an :data:`Ending`), or None without one."""
    starts = [i for i, record in enumerate(records) if record.get('event') == 'start']
    if not starts:
        return None
    mission = records[starts[-1]:]
    name, steps = mission[0].get('mission', '?'), mission[0].get('steps', 0)
    said = [record for record in mission if record.get('event') == 'say']
    step = said[-1].get('step', 0) if said else 0
    end = next((record for record in mission if record.get('event') == 'end'), None)
    if end is not None:
        return Ending(name, end['status'], end['message'], step, steps)
    last = said[-1]['text'] if said else 'nothing'
    return Ending(name, 'interrupted', 'the executive stopped during step %d of %d; the last it said: %s'
                  % (step, steps, last), step, steps)


def describe(ending):
    """One line for the operator: how the last mission ended."""
    if ending is None:
        return 'no mission in the log'
    return 'last mission %s: %s (%s)' % (ending.mission, ending.status, ending.message)
