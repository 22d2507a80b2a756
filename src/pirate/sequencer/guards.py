"""Guard tables of the motion primitives, loaded from config (never in code).

``config/guards_<mm>.yaml`` hold the per-diameter values of report Tables
5.2 and 5.3, ``config/sequencer.yaml`` what is common (timeouts, regions of
Table 5.4, drive settings). The manager loads them on the parameter server;
tests load the files directly. Pure Python.
"""
import collections
import os

import yaml

from pirate import paths

#: One bend's part of a clamp/unclamp: setpoint (counts) and guard (rad).
BendGuard = collections.namedtuple('BendGuard', 'joint setpoint guard')


class PairGuard(collections.namedtuple('PairGuard', 'kind outer inner')):
    """A two-bend primitive: outer (alpha) and inner (beta) bend (SPEC 7)."""

    __slots__ = ()

    def closed(self, angles, margin_rad=0.0):
        """Clamp guard: outer at least this negative, inner at least this positive (less ``margin_rad``)."""
        return (angles[self.outer.joint] <= self.outer.guard + margin_rad
                and angles[self.inner.joint] >= self.inner.guard - margin_rad)

    def opened(self, angles, margin_rad=0.0):
        """Unclamp guard: both bends back at least this close to 0 (less ``margin_rad``)."""
        return (angles[self.outer.joint] >= self.outer.guard - margin_rad
                and angles[self.inner.joint] <= self.inner.guard + margin_rad)

    def describe(self, closing):
        """The guard as text, for feedback and logs."""
        outer, inner = ('<=', '>=') if closing else ('>=', '<=')
        return '%s %s %.2f and %s %s %.2f' % (self.outer.joint, outer, self.outer.guard,
                                              self.inner.joint, inner, self.inner.guard)


#: A one-joint move: setpoint (counts) until the joint passes guard (rad).
MoveGuard = collections.namedtuple('MoveGuard', 'kind setpoint guard')

#: Which bends make each clamp (SPEC 2): (outer, inner).
CLAMP_BENDS = {'front': ('bend_i', 'bend_ii'), 'rear': ('bend_iv', 'bend_iii')}

CONFIG_DIR = paths.CONFIG_DIR


class NoGuards(KeyError):
    """The configuration has no guards for this primitive / diameter."""

    def __str__(self):
        return self.args[0]


class Guards(object):
    """The guards of one pipe diameter, plus the common sequencer settings."""

    def __init__(self, table, common):
        self.pipe_diameter = int(table['pipe_diameter'])
        self._table = table
        self.common = common

    def pair(self, kind, part):
        """:class:`PairGuard` of primitive ``kind`` (e.g. 'clamp') for ``part``."""
        key = kind
        if kind.startswith('unclamp') and not kind.startswith('unclamp_partial'):
            key = 'unclamp_%s' % part
        entry = self._table.get(key)
        if entry is None:
            raise NoGuards('no guards for %s in a %d mm pipe' % (key, self.pipe_diameter))
        outer, inner = CLAMP_BENDS[part]
        return PairGuard(key,
                         BendGuard(outer, int(entry['outer']['setpoint']), float(entry['outer']['guard'])),
                         BendGuard(inner, int(entry['inner']['setpoint']), float(entry['inner']['guard'])))

    def move(self, kind):
        """:class:`MoveGuard` of a front-module move ('move_front', ...)."""
        entry = self._table.get(kind, self.common.get(kind))
        if entry is None:
            raise NoGuards('no guards for %s in a %d mm pipe' % (kind, self.pipe_diameter))
        return MoveGuard(kind, int(entry['setpoint']), float(entry['guard']))

    def has(self, kind):
        """True when this diameter has guards for ``kind``."""
        return kind in self._table

    def row(self, key):
        """The raw row ``key`` of this diameter's table (e.g. ``clamp_state``)."""
        if key not in self._table:
            raise NoGuards('no %s row for a %d mm pipe' % (key, self.pipe_diameter))
        return self._table[key]

    def region(self, name):
        """(low, high) rad of orientation region 'straight' or 'nominal'."""
        low, high = self.common['regions'][name]
        return float(low), float(high)

    def __getattr__(self, name):
        try:
            return self.common[name]
        except KeyError:
            raise AttributeError(name)


def load_files(config_dir=CONFIG_DIR):
    """Read every guards_<mm>.yaml and sequencer.yaml: ({mm: table}, common)."""
    tables = {}
    for name in sorted(os.listdir(config_dir)):
        if name.startswith('guards_') and name.endswith('.yaml'):
            with open(os.path.join(config_dir, name)) as stream:
                table = yaml.safe_load(stream)
            tables[int(table['pipe_diameter'])] = table
    with open(os.path.join(config_dir, 'sequencer.yaml')) as stream:
        common = yaml.safe_load(stream)
    return tables, common


class BadConfig(ValueError):
    """A sequencer setting that is missing, not a number, or out of its range."""


#: Safety settings of config/sequencer.yaml and their allowed ranges
#: (checked at load: a bad setting is refused, never silently accepted). Key path -> (low, high).
RANGES = {
    ('primitive_timeout',): (1.0, 60.0),
    ('feedback_timeout',): (0.05, 2.0),
    ('wall_timeout_factor',): (1.0, 10.0),
    ('max_primitives',): (1, 200),
    ('re_adjust', 'same_roll_passes'): (2, 20),
    ('re_adjust', 'same_roll_rad'): (0.001, 0.2),
    ('align_tolerance',): (0.001, 0.2),
    ('rotate_tolerance',): (0.001, 0.2),
    ('drive', 'default_speed'): (1.0, 170.0),
    ('drive', 'max_distance'): (1.0, 20000.0),
    ('drive', 'creep_speed'): (1.0, 170.0),
    ('drive', 'creep_lead'): (0.0, 5.0),
    ('drive', 'stop_lead'): (0.0, 5.0),
    ('drive', 'tolerance'): (0.5, 100.0),
    ('drive', 'no_progress_s'): (0.1, 5.0),
    ('drive', 'no_progress_mm'): (0.1, 50.0),
    ('drive', 'no_progress_start_s'): (0.0, 5.0),
    ('drive', 'time_margin_s'): (0.1, 30.0),
    ('manual', 'no_progress_s'): (0.5, 30.0),
    ('manual', 'wheel_progress_mm'): (0.5, 100.0),
    ('manual', 'wheel_spread'): (0.1, 1.0),
    ('manual', 'joint_progress_rad'): (0.001, 0.1),
    ('unclamp', 'no_progress_s'): (0.5, 15.0),
    ('unclamp', 'no_progress_rad'): (0.001, 0.1),
    ('unclamp', 'no_progress_mnm'): (1.0, 100.0),
}


def check_common(common):
    """Raise :class:`BadConfig` naming every setting that is missing or out of range."""
    problems = []
    for path, (low, high) in sorted(RANGES.items()):
        value = common
        for key in path:
            value = value.get(key) if isinstance(value, dict) else None
        name = '/'.join(path)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            problems.append('%s = %r is not a number' % (name, value))
        elif not low <= value <= high:
            problems.append('%s = %r outside [%g, %g]' % (name, value, low, high))
    if problems:
        raise BadConfig('sequencer settings refused: ' + '; '.join(problems))


class GuardBook(object):
    """All diameters: ``book.for_diameter(90)`` or NoGuards with the reason.

    ``tables`` maps any key (a param name such as ``pipe90``) to a table;
    each table names its own ``pipe_diameter``.
    """

    def __init__(self, tables, common):
        check_common(common)
        self._tables = {int(t['pipe_diameter']): t for t in tables.values()}
        self.common = common

    def diameters(self):
        """Pipe diameters (mm) that have guards."""
        return sorted(self._tables)

    def for_diameter(self, mm):
        """:class:`Guards` of pipe diameter ``mm``."""
        if mm not in self._tables:
            raise NoGuards('no guards for a %s mm pipe (configured: %s mm)'
                           % (mm, ', '.join(str(d) for d in self.diameters())))
        return Guards(self._tables[mm], self.common)
