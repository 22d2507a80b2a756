"""Where each constant of the physics twin comes from: one table.

config/twin.yaml holds the values the twin runs on; config/twin_sources.yaml
says, keyed by each constant's dotted name (``bend.stall_nm``), its
``kind`` and one line of ``source``, and by kind:

- ``report``: ``section`` of the 2016 report (and ``page``);
- ``datasheet``: the part's datasheet, named in ``source``;
- ``measured``: on the real robot, ``row``: its doc/measurements.md row;
- ``fitted``: the ``experiment`` it is fitted to and the ``bench``
  (script and option) that refits it;
- ``estimate``: the ``range`` [low, high] it could take on the real robot
  (a list value: one [low, high] per element);
- ``choice``: a modelling or numerical choice (``row``: the figure behind it).

The twin reads only twin.yaml; the ranges are for an uncertainty sweep
(:func:`drawn`: a robot of the ranges, doc/sweeps.md#drawn-robots).
:func:`problems` is what test/unit/test_twin_sources.py checks;
:func:`markdown` is the table in doc/twin.md (``make docs``). Pure apart
from :func:`load` and :func:`problems` reading files.
"""
import collections
import copy
import io
import os
import random
import re

import yaml

from pirate import paths
from pirate.sim import twin_model

SOURCES_FILE = os.path.join(paths.CONFIG_DIR, 'twin_sources.yaml')
MEASUREMENTS = os.path.join('doc', 'measurements.md')
KINDS = ('report', 'datasheet', 'measured', 'fitted', 'estimate', 'choice')
FIELDS = ('kind', 'source', 'section', 'page', 'experiment', 'bench', 'range', 'row')
#: A report section (2.4.3.1), table or figure (Table 6.1, Fig 2.11).
SECTION = re.compile(r'^(\d+\.\d+(\.\d+)*|Table \d+\.\d+|Fig \d+\.\d+)\b')
EXPERIMENT = re.compile(r'\b(Table|Fig) \d+\.\d+')

Constant = collections.namedtuple('Constant', 'name value kind source section page experiment bench range row')


def load(config_path=twin_model.CONFIG_FILE, sources_path=SOURCES_FILE):
    """(twin.yaml's constants, twin_sources.yaml's entries) as loaded."""
    with io.open(sources_path, encoding='utf-8') as stream:
        return twin_model.load_config(config_path), yaml.safe_load(stream)


def leaves(config, prefix=''):
    """{'section.key': value} of every constant, in the file's order; a list is one value."""
    found = collections.OrderedDict()
    for key, value in config.items():
        name = prefix + str(key)
        if isinstance(value, dict):
            found.update(leaves(value, name + '.'))
        else:
            found[name] = value
    return found


def drawn(seed, config=None, sources=None):
    """(config, {name: value drawn}): config/twin.yaml (or ``config``) with
    every constant that has a plausible range drawn uniformly from it (a list
    element by element; an integer stays one), from ``seed`` alone."""
    if config is None or sources is None:
        config, sources = load()
    rng, robot, changes = random.Random('robot %d' % seed), copy.deepcopy(config), collections.OrderedDict()
    for constant in constants(config, sources):
        if constant.range is None:
            continue
        pairs = zip(range_pairs(constant), _as_list(constant.value))
        values = [_draw(rng, low, high, value) for (low, high), value in pairs]
        section, key = constant.name.split('.')
        robot[section][key] = changes[constant.name] = values if isinstance(constant.value, list) else values[0]
    return robot, changes


def range_pairs(constant):
    """[(low, high)] of ``constant``'s plausible range, one per element of a list value."""
    return constant.range if isinstance(constant.value, list) else [constant.range]


def _draw(rng, low, high, nominal):
    value = rng.uniform(low, high)
    return int(round(value)) if isinstance(nominal, int) and not isinstance(nominal, bool) else value


def _as_list(value):
    return value if isinstance(value, list) else [value]


def _entry(sources, name):
    entry = sources.get(name)
    return entry if isinstance(entry, dict) else {}


def constants(config, sources):
    """Every constant of ``config`` with what ``sources`` says of it (None where nothing)."""
    return [Constant(name, value, **{field: _entry(sources, name).get(field) for field in FIELDS})
            for name, value in leaves(config).items()]


def problems(config, sources, root=paths.PACKAGE_DIR):
    """What is wrong with ``sources`` for ``config``: a list of sentences, empty when nothing."""
    found = ['%s: an entry for no constant of twin.yaml' % name for name in sources if name not in leaves(config)]
    for constant in constants(config, sources):
        if not isinstance(sources.get(constant.name), dict):
            found.append('%s: no entry' % constant.name)
            continue
        found.extend('%s: %s' % (constant.name, text)
                     for text in _entry_problems(constant, sources[constant.name], root))
    return found


def _entry_problems(constant, entry, root):
    found = ['unknown field %s' % field for field in entry if field not in FIELDS]
    if constant.kind not in KINDS:
        return found + ['kind %r is none of %s' % (constant.kind, ', '.join(KINDS))]
    if not constant.source:
        found.append('no source')
    if constant.kind == 'report' and not SECTION.match(str(constant.section or '')):
        found.append('a report source names no section (e.g. "2.4.3.1", "Table 6.5")')
    if constant.kind == 'fitted':
        found.extend(_fit_problems(constant, root))
    if constant.kind == 'measured' and not constant.row:
        found.append('a measured constant names no row of %s' % MEASUREMENTS)
    if constant.kind == 'estimate' or constant.range is not None:
        found.extend(_range_problems(constant.value, constant.range))
    if constant.row and 'id="%s"' % constant.row not in _read(root, MEASUREMENTS):
        found.append('no row %s in %s' % (constant.row, MEASUREMENTS))
    return found


def _fit_problems(constant, root):
    if not EXPERIMENT.search(str(constant.experiment or '')):
        return ['a fitted constant names no experiment (a report table or figure)']
    script, _, option = str(constant.bench or '').partition(' ')
    if not script or not os.path.isfile(os.path.join(root, script)):
        return ['its bench %r does not exist' % script]
    text = _read(root, script)
    if not option or "'%s'" % option not in text:
        return ['%s has no option %r' % (script, option)]
    if constant.name not in text:
        return ['%s does not fit it' % script]
    return []


def _range_problems(value, plausible):
    """Why ``plausible`` is no [low, high] holding ``value`` (a list: one per element)."""
    if isinstance(value, list):
        if not (isinstance(plausible, list) and len(plausible) == len(value)
                and all(isinstance(pair, list) for pair in plausible)):
            return ['an estimate of %d values needs one [low, high] per value' % len(value)]
        return [text for v, r in zip(value, plausible) for text in _range_problems(v, r)]
    if not (isinstance(plausible, list) and len(plausible) == 2 and all(_number(x) for x in plausible)):
        return ['an estimate needs a range [low, high], not %r' % (plausible,)]
    low, high = plausible
    if low > high:
        return ['range [%g, %g]: low above high' % (low, high)]
    if not _number(value) or not low <= value <= high:
        return ['range [%g, %g] does not hold the value %r' % (low, high, value)]
    return []


def _number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _read(root, path):
    with io.open(os.path.join(root, path), encoding='utf-8') as stream:
        return stream.read()


def _show(value):
    if isinstance(value, list):
        return '[%s]' % ', '.join(_show(v) for v in value)
    if isinstance(value, bool):
        return str(value).lower()
    return '%g' % value if _number(value) else str(value)


def _where(constant):
    """The source column: the report's place, the fit, the source line, the row."""
    text = constant.source
    if constant.kind == 'report':
        page = ', p. %s' % constant.page if constant.page is not None else ''
        text = '%s%s: %s' % (constant.section, page, text)
    if constant.kind == 'fitted':
        text += '; to %s, refitted by `%s`' % (constant.experiment, constant.bench)
    if constant.row:
        text += ' ([%s](measurements.md#%s))' % (constant.row, constant.row)
    return text


def _plausible(constant):
    if constant.range is None:
        return ''
    return ', '.join('%s to %s' % (_show(low), _show(high)) for low, high in range_pairs(constant))


def markdown(config=None, sources=None):
    """The constants table of doc/twin.md, from the two files (or the given contents)."""
    if config is None or sources is None:
        config, sources = load()
    rows = ['| constant | value | kind | source | plausible range |', '|---|---|---|---|---|']
    rows.extend('| `%s` | %s | %s | %s | %s |' % (c.name, _show(c.value), c.kind, _where(c), _plausible(c))
                for c in constants(config, sources))
    counts = collections.Counter(c.kind for c in constants(config, sources))
    rows.append('')
    rows.append('%d constants: %s.' % (sum(counts.values()),
                                       ', '.join('%d %s' % (counts[k], k) for k in KINDS if counts[k])))
    return '\n'.join(rows)
