"""A sweep's cases: a table of parameters, a seed each.

A case is a dict: ``key`` (its name in the records, unique in the sweep),
``group`` (the table row it counts in), ``params`` (what the case function
takes, JSON values) and ``seed``. Seeds are drawn from the sweep's seed and
the case's key, so a case keeps its seed whatever other cases the sweep
has or in what order they run.
"""
import zlib


class SweepError(ValueError):
    """Bad input to a sweep: said before any case runs."""


class Sweep(object):
    """What a bench declares: its ``name``, the parameters its cases take
    (``parameters``, names), ``run`` (a module-level function of the bench
    ``run(params, seed, settings)`` -> one record's fields, a dict, or a list
    of them, one per variant: see :func:`pirate.sweep.records.complete`),
    ``check(cases, settings)`` (errors, a list of strings: a world that does
    not load, ...; optional) and the wall seconds a case may take before it
    counts as hung (``time_limit_s``); ``summary(records)``: lines the runner
    prints under the table (optional)."""

    def __init__(self, name, parameters, run, check=None, time_limit_s=600.0, summary=None):
        self.name = name
        self.parameters = tuple(parameters)
        self.run = run
        self.check = check or (lambda cases, settings: [])
        self.time_limit_s = time_limit_s
        self.summary = summary or (lambda records: [])


def key_of(params, names):
    """The case's key: its parameters in ``names`` order, ``name=value`` joined by spaces (None left out)."""
    return ' '.join('%s=%s' % (name, _text(params[name])) for name in names if params.get(name) is not None)


def _text(value):
    if isinstance(value, float):
        return '%g' % value
    if isinstance(value, dict):
        return ','.join('%s:%s' % (k, _text(v)) for k, v in sorted(value.items())) or '-'
    if isinstance(value, (list, tuple)):
        return ','.join(_text(v) for v in value) or '-'
    return str(value)


def seed_of(sweep_seed, key):
    """A case's seed (0 .. 2**31 - 1): from the sweep's seed and the case's key only."""
    return zlib.crc32(('%d %s' % (sweep_seed, key)).encode('utf-8')) & 0x7fffffff


def case(sweep, params, group, sweep_seed):
    """One case of ``sweep``: ``params`` (checked against its parameters), its
    ``group`` (table row) and its seed."""
    unknown = sorted(set(params) - set(sweep.parameters))
    if unknown:
        raise SweepError('%s: unknown case parameter(s) %s (it takes %s)'
                         % (sweep.name, ', '.join(unknown), ', '.join(sweep.parameters)))
    key = key_of(params, sweep.parameters)
    return {'key': key, 'group': group, 'params': dict(params), 'seed': seed_of(sweep_seed, key)}


def unique(cases):
    """``cases`` with every key once; raises on two cases of one key with different parameters."""
    seen = {}
    for one in cases:
        if one['key'] in seen and seen[one['key']]['params'] != one['params']:
            raise SweepError('two cases named %r' % one['key'])
        seen.setdefault(one['key'], one)
    return list(seen.values())


def parse_filters(texts, sweep):
    """``--case NAME=VALUE`` filters: {name: value text}; an unknown name is a :class:`SweepError`."""
    filters = {}
    for text in texts or ():
        name, sep, value = text.partition('=')
        if not sep:
            raise SweepError('--case %r: NAME=VALUE expected' % text)
        if name not in sweep.parameters:
            raise SweepError('--case %s: unknown case parameter %r (%s takes %s)'
                             % (text, name, sweep.name, ', '.join(sweep.parameters)))
        filters.setdefault(name, set()).add(value)
    return filters


def select(cases, filters):
    """The cases whose parameters match every filter (a value as the key writes it)."""
    return [one for one in cases
            if all(_text(one['params'].get(name)) in values for name, values in filters.items())]


def seeds_line(cases, sweep_seed, shown=8):
    """What the runner prints about the seeds it drew."""
    listed = ' '.join('%d' % one['seed'] for one in cases[:shown])
    more = ' ... (%d more; every seed is in its record)' % (len(cases) - shown) if len(cases) > shown else ''
    return 'sweep seed %d; case seeds drawn: %s%s' % (sweep_seed, listed, more)
