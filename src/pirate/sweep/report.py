"""The sweep's table from its records, and two sweeps compared case by case.

A row per group (and variant) of cases, in the order the sweep declared
them: runs, success, how many of each outcome, the median and worst robot
seconds and the median primitives of the runs that succeeded, then the
bench's figures (median and range). Two sweeps: the same rows side by side,
a row whose success, false successes or durations differ flagged ``*``,
then every case whose outcome differs.
"""
import collections
import re
import statistics

SUCCESS, FALSE_SUCCESS = 'succeeded', 'FALSE success'
#: Outcome columns in this order first; any other outcome after them, alphabetically.
ORDER = (SUCCESS, FALSE_SUCCESS, 'refused', 'aborted', 'preempted', 'livelock', 'lost state', 'hang', 'crashed')
#: Durations further apart than this fraction (and a Mega cycle) are a difference.
DURATION_TOLERANCE = 0.10
MEGA_CYCLE_S = 0.1
#: A number in a reason (a guard's value, a time, a count): '#' when reasons are counted alike.
NUMBER = re.compile(r'[-+]?\d+(\.\d+)?')


def label(record):
    return record['group'] + (', ' + record['variant'] if record.get('variant') else '')


def grouped(records):
    """[(label, records)] in the order the sweep declared their cases (else their records came)."""
    groups = {}
    for record in sorted(records, key=_place):
        groups.setdefault(label(record), []).append(record)
    return list(groups.items())


def by_robot(records):
    """``records`` regrouped a row per robot they ran on (``robot`` k of
    ``--robots``, doc/sweeps.md#drawn-robots; the nominal twin first)."""
    return [dict(record, group='robot %d' % number if number else 'nominal twin', variant=None, index=number or 0)
            for record, number in ((r, r['params'].get('robot')) for r in records)]


def screened(records, screen):
    """(records of the robots that succeeded in every record of ``screen``
    they have there, those robots' numbers): a sweep restricted to the drawn
    robots that do what another sweep asks (e.g. Chapter 6's experiments,
    which the real robot did). Records of the nominal twin stay."""
    failed = {r['params'].get('robot') for r in screen if r['outcome'] != SUCCESS}
    passed = {r['params'].get('robot') for r in screen} - failed - {None}
    return [r for r in records if r['params'].get('robot') in passed | {None}], sorted(passed)


def _place(record):
    index = record.get('index')
    return (0, index) if index is not None else (1, 0)


def outcomes(records):
    present = {record['outcome'] for record in records}
    return [o for o in ORDER if o in present or o in (SUCCESS, FALSE_SUCCESS)] + sorted(present - set(ORDER))


def figures_of(runs):
    """(median robot s, worst robot s, median primitives) of the runs that succeeded, or Nones."""
    done = [r for r in runs if r['outcome'] == SUCCESS and r.get('robot_s') is not None]
    if not done:
        return None, None, None
    seconds = [r['robot_s'] for r in done]
    return statistics.median(seconds), max(seconds), statistics.median(len(r['primitives']) for r in done)


def _number(value, form='%.1f'):
    return form % value if value is not None else '-'


def table(records, width=44):
    """The sweep's table: a line per group, a line of its figures under it."""
    columns = outcomes(records)
    names = [('FALSE' if c == FALSE_SUCCESS else c) for c in columns]
    widths = [max(5, len(name)) for name in names]
    heads = ' '.join('%*s' % w for w in zip(widths, names))
    lines = ['%-*s %4s %7s %s  %s' % (width, 'case', 'n', 'success', heads, 'median / worst s, median primitives')]
    for name, runs in grouped(records):
        counts = [sum(1 for r in runs if r['outcome'] == c) for c in columns]
        median, worst, prims = figures_of(runs)
        lines.append('%-*s %4d %6.0f%% %s  %s / %s s, %s' % (
            width, name[:width], len(runs), 100.0 * counts[0] / len(runs),
            ' '.join('%*d' % wc for wc in zip(widths, counts)), _number(median), _number(worst),
            _number(prims, '%.0f')))
        lines += wrapped(bench_figures(runs))
    return lines


def wrapped(parts, width=110):
    """``parts`` joined by '; ' into indented lines of at most about ``width`` characters."""
    lines, line = [], ''
    for part in parts:
        if line and len(line) + len(part) > width:
            lines.append('    ' + line + ';')
            line = ''
        line += ('; ' if line else '') + part
    return lines + (['    ' + line] if line else [])


def bench_figures(runs):
    """['name median m [low, high]', ...] of the bench's own figures in these runs."""
    names = sorted({name for r in runs for name in r.get('figures', {})})
    parts = []
    for name in names:
        values = [r['figures'][name] for r in runs if r.get('figures', {}).get(name) is not None]
        if values:
            parts.append('%s %.4g [%.4g, %.4g]' % (name, statistics.median(values), min(values), max(values)))
    return parts


def reasons_lines(records, width=100):
    """Per group, why its runs did not succeed: each reason once, its numbers
    as '#' (a guard's value, a time), most frequent first, with its count and outcome."""
    lines = []
    for name, runs in grouped(records):
        why = collections.Counter((r['outcome'], NUMBER.sub('#', r.get('reason') or '')[:width])
                                  for r in runs if r['outcome'] != SUCCESS)
        if why:
            lines.append(name)
            lines.extend('  %3d %s: %s' % (count, outcome, reason) for (outcome, reason), count in why.most_common())
    return lines


def cases_lines(records):
    """One line per record: its case, outcome, robot seconds and reason."""
    return ['%-60s %-14s %6s s  %s' % (r['key'] + (' ' + r['variant'] if r.get('variant') else ''), r['outcome'],
                                       _number(r.get('robot_s')), r.get('reason', '')[:100]) for r in records]


def _differs(a, b):
    """Two durations (None: none) differ beyond the tolerance."""
    if a is None or b is None:
        return (a is None) != (b is None)
    return abs(a - b) > max(MEGA_CYCLE_S, DURATION_TOLERANCE * max(abs(a), abs(b)))


def compare(a_records, b_records, width=36):
    """Sweep A against sweep B: per group, then per case whose outcome differs."""
    lines = ['%-*s %9s %9s %9s %15s %15s' % (width, 'case (A -> B)', 'n', 'success', 'FALSE', 'median s', 'worst s')]
    a_groups, b_groups = dict(grouped(a_records)), dict(grouped(b_records))
    names = [n for n, _ in grouped(a_records)] + [n for n, _ in grouped(b_records) if n not in a_groups]
    for name in names:
        a, b = a_groups.get(name, []), b_groups.get(name, [])
        (am, aw, _), (bm, bw, _) = figures_of(a), figures_of(b)
        a_ok, b_ok = (sum(1 for r in runs if r['outcome'] == SUCCESS) for runs in (a, b))
        a_false, b_false = (sum(1 for r in runs if r['outcome'] == FALSE_SUCCESS) for runs in (a, b))
        flag = a_ok != b_ok or a_false != b_false or _differs(am, bm) or _differs(aw, bw) or len(a) != len(b)
        lines.append('%-*s %4d->%-4d %4d->%-4d %4d->%-4d %6s->%-6s %6s->%-6s %s' % (
            width, name[:width], len(a), len(b), a_ok, b_ok, a_false, b_false, _number(am), _number(bm),
            _number(aw), _number(bw), '*' if flag else ''))
    return lines + case_differences(a_records, b_records)


def _by_case(records):
    return {(r['key'], r.get('variant', '')): r for r in records}


def case_differences(a_records, b_records):
    """Lines for the cases whose outcome differs, and those in one sweep only."""
    a, b = _by_case(a_records), _by_case(b_records)
    both = [k for k in a if k in b]
    changed = [k for k in both if a[k]['outcome'] != b[k]['outcome']]
    slower = [k for k in both if k not in changed and _differs(a[k].get('robot_s'), b[k].get('robot_s'))]
    lines = ['%d cases in both: %d differ in outcome, %d in duration only; %d only in A, %d only in B'
             % (len(both), len(changed), len(slower), len(set(a) - set(b)), len(set(b) - set(a)))]
    for key in changed:
        lines.append('* %s%s: %s -> %s (%s s -> %s s)  B: %s' % (
            key[0], ' ' + key[1] if key[1] else '', a[key]['outcome'], b[key]['outcome'],
            _number(a[key].get('robot_s')), _number(b[key].get('robot_s')), b[key].get('reason', '')[:80]))
    for key in slower:
        lines.append('  %s%s: %s, %s s -> %s s' % (key[0], ' ' + key[1] if key[1] else '', a[key]['outcome'],
                                                   _number(a[key].get('robot_s')), _number(b[key].get('robot_s'))))
    return lines
