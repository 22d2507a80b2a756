"""Records: one JSON object per line, one file per sweep.

The first line is the sweep's header (``{"sweep": {...}}``: its name, its
settings, its seed); then one record per case (per variant of a case), as
it finished. A record holds:

- ``key``, ``group``, ``variant``, ``params``, ``seed``: the case;
  ``index``, its place in the sweep (the table's order);
- ``outcome`` ('succeeded', 'FALSE success', 'refused', 'aborted', 'hang',
  'crashed', or a bench's own word) and ``reason``;
- ``robot_s`` (the run's duration, robot seconds), ``primitives`` (the
  motion primitives it executed, in order), ``truth`` (the ground truth's
  verdict, ``verdict`` true / false / null, and what it read), ``figures``
  (the bench's numbers: name -> number);
- ``commit``, ``mujoco``: the code and engine that ran it; ``attempts``;
  ``wall_s``, ``host`` and ``worker`` (how long, on which machine and Dask
  worker: not part of the result).

Any JSON reader opens the file (``python3 -m json.tool``, pandas'
``read_json(lines=True)``, ``jq``).
"""
import io
import json
import os

#: Fields that say where, how long and in what place of the sweep a case ran, not what it gave:
#: left out when records are compared.
WALL_FIELDS = ('wall_s', 'host', 'worker', 'attempts', 'index')
#: What a record holds besides the case; a case function's dict may set these.
RESULT_FIELDS = ('variant', 'outcome', 'reason', 'robot_s', 'primitives', 'truth', 'figures')


def complete(case, result, provenance):
    """The record of ``case`` from one dict its function returned (``outcome``
    required) and ``provenance`` (``commit``, ``mujoco``, ``host``, ...)."""
    unknown = sorted(set(result) - set(RESULT_FIELDS))
    if unknown or 'outcome' not in result:
        raise ValueError('a case result has the fields %s; it may have %s and must have outcome'
                         % (', '.join(sorted(result)), ', '.join(RESULT_FIELDS)))
    record = {'key': case['key'], 'group': case['group'], 'variant': result.get('variant', ''),
              'params': case['params'], 'seed': case['seed'], 'outcome': result['outcome'],
              'reason': result.get('reason', ''), 'robot_s': result.get('robot_s'),
              'primitives': list(result.get('primitives', ())), 'truth': result.get('truth', {}),
              'figures': result.get('figures', {}), 'index': case.get('index')}
    record.update(provenance)
    return record


def failed(case, outcome, reason, attempts, provenance):
    """The record of a case that crashed or hung on every attempt (``provenance``: the runner's)."""
    record = complete(case, {'outcome': outcome, 'reason': reason}, provenance)
    record['attempts'] = attempts
    return record


def header(name, settings, sweep_seed):
    """The sweep's first line, as it reads back (tuples become lists)."""
    return json.loads(json.dumps({'sweep': {'name': name, 'settings': settings, 'seed': sweep_seed}}))


class Writer(object):
    """Appends records to ``path``, each line written whole and flushed as it comes."""

    def __init__(self, path, head=None):
        directory = os.path.dirname(path)
        if directory:
            os.makedirs(directory, exist_ok=True)
        self.path = path
        self._file = io.open(path, 'a', encoding='utf-8')
        if head is not None:
            self.write([head])

    def write(self, lines):
        self._file.write(''.join(json.dumps(line, sort_keys=True) + '\n' for line in lines))
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self):
        self._file.close()


def read(path):
    """(header or None, records) of a sweep file; a last line cut short (the
    sweep was killed while writing it) is left out, any other bad line raises."""
    with io.open(path, encoding='utf-8') as source:
        lines = source.read().split('\n')
    head, records = None, []
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            item = json.loads(line)
        except ValueError:
            if number == len(lines):
                break
            raise ValueError('%s line %d is not a record: %.60s' % (path, number, line))
        if 'sweep' in item:
            head = item['sweep']
        else:
            records.append(item)
    return head, records


def finished(records):
    """The keys of the cases that have a record (``--resume`` skips them)."""
    return {record['key'] for record in records}


def comparable(record):
    """``record`` without where and how long it ran: what the same seed and code must give again."""
    return {name: value for name, value in record.items() if name not in WALL_FIELDS}
