"""An inspection job's run on the twin, judged: for bench/mission_sweep ``--job``.

While the mission runs, :class:`MarkWatch` decides when each of the job's
marks falls due exactly as the job node does (pirate.inspection.job
DueMarks, fed the executive's estimate and its steps' signed distances)
and keeps, for each, the estimate that made it due and where the twin
says the robot's middle is at that moment. After the run :func:`judge`
says how it ended and :func:`summary_lines` prints the runs and the
totals from their records. Pure: the estimate and the truth are functions
the caller gives.
"""
import collections
import statistics
import threading

from pirate.inspection.job import LEGS

#: Back at the route's last point within this (mm, ground truth): the run's verdict.
ARRIVE_MM = 50.0
#: One mark fallen due: the mark, the estimate that made it due and the true position then (mm along the
#: map), and the number of the mission's step that ran (None before the first).
Seen = collections.namedtuple('Seen', 'mark estimate_mm truth_mm step')


class MarkWatch(object):
    """``estimate_mm()``: the executive's estimate of the robot's middle now
    (None before the robot reports); ``truth_mm()``: the twin's. :meth:`step`
    from the executive's progress, :meth:`check` and :meth:`record` between
    robot cycles (pirate.testing.harness.SimHarness.when)."""

    def __init__(self, due, estimate_mm, truth_mm):
        self._due = due
        self._estimate_mm, self._truth_mm = estimate_mm, truth_mm
        self._lock = threading.Lock()
        self._pending = []
        self._step = None
        self.seen = []

    def step(self, distance_mm, number=None, pab=''):
        """The mission's running step (``number``) is PAB ``pab`` with the signed distance ``distance_mm``."""
        with self._lock:
            self._due.step(distance_mm, pab, number)
            self._step = number

    def check(self):
        """Feed the estimate now; True when a mark fell due (then :meth:`record`)."""
        along_mm = self._estimate_mm()
        if along_mm is None:
            return False
        with self._lock:
            self._pending += [(mark, along_mm, self._step) for mark in self._due.passed(along_mm)]
            return bool(self._pending)

    def record(self):
        """Where the twin has the robot for every mark fallen due since the last call."""
        with self._lock:
            pending, self._pending = self._pending, []
        if pending:
            truth_mm = self._truth_mm()
            self.seen += [Seen(mark, along_mm, truth_mm, step) for mark, along_mm, step in pending]

    def left(self):
        """The marks not yet due."""
        with self._lock:
            return self._due.left()


def figure_name(mark):
    """The record's figure of one mark's error: 'mark_in_800_mm'."""
    return 'mark_%s_%.0f_mm' % (mark.leg, mark.along_mm)


def mark_figures(seen):
    """{figure name: estimate - truth, mm} of every mark fallen due, and
    ``step_of_<figure name>``: the step that ran then."""
    figures = {figure_name(s.mark): s.estimate_mm - s.truth_mm for s in seen}
    figures.update(('step_of_' + figure_name(s.mark), s.step) for s in seen if s.step is not None)
    return figures


def judge(mission_status, goal_statuses, arrive_mm, marks_left):
    """(outcome, why) of a run: ``succeeded`` only when the mission succeeded
    with every PAB it sent succeeding (``goal_statuses``), the robot's middle
    ends within :data:`ARRIVE_MM` of the route's last point by ground truth
    (``arrive_mm``) and every mark fell due (``marks_left`` none)."""
    if mission_status != 'succeeded':
        return mission_status, ''
    if abs(arrive_mm) > ARRIVE_MM:
        return 'FALSE success', 'the robot ended %.0f mm from the last point (within %.0f needed)' % (
            arrive_mm, ARRIVE_MM)
    if marks_left:
        return 'marks missed', '%d mark(s) never fell due' % len(marks_left)
    failed = sum(1 for status in goal_statuses if status != 'succeeded')
    if failed:
        return 'retried', '%d PAB(s) did not succeed; the mission retried them' % failed
    return 'succeeded', ''


def leg_errors(records, leg):
    """|estimate - truth| (mm) at every mark of ``leg`` in ``records``."""
    prefix = 'mark_%s_' % leg
    return [abs(value) for record in records for name, value in sorted(record.get('figures', {}).items())
            if name.startswith(prefix)]


def _spread(values, form='%.0f'):
    if not values:
        return '-'
    return (form + ' / ' + form) % (statistics.median(values), max(values))


def run_line(record):
    """One run: its seed, start roll, outcome, s/m, end error and each mark's error."""
    figures = record.get('figures', {})
    names = sorted((name for name in figures if name.startswith('mark_')), key=_mark_order)
    marks = ', '.join('%s %+.0f%s' % (name[len('mark_'):-len('_mm')], figures[name],
                                      ' (step %d)' % figures['step_of_' + name] if 'step_of_' + name in figures
                                      else '') for name in names)
    roll = figures.get('start_roll_rad')
    return '%s seed %d roll %s: %s%s; %s s/m; end %s mm; marks (estimate - truth, mm): %s' % (
        record['key'], record['seed'], '%.1f deg' % (roll * 57.29577951308232) if roll is not None else '-',
        record['outcome'], ' (%s)' % record['reason'][:90] if record['outcome'] != 'succeeded' else '',
        '%.1f' % figures['s_per_m'] if 's_per_m' in figures else '-',
        '%+.0f' % figures['arrive_err_mm'] if 'arrive_err_mm' in figures else '-', marks or 'none')


def _mark_order(name):
    """'mark_in_800_mm' -> (0, 800.0): in before back, then along."""
    _, leg, along, _ = name.split('_')
    return LEGS.index(leg), float(along)


def summary_lines(records):
    """Every run, then the totals: success, s/m, the marks' errors in and back (median / worst)."""
    lines = [run_line(record) for record in sorted(records, key=lambda r: r.get('index') or 0)]
    ok = sum(1 for record in records if record['outcome'] == 'succeeded')
    per_m = [record['figures']['s_per_m'] for record in records
             if record['outcome'] == 'succeeded' and 's_per_m' in record.get('figures', {})]
    share = 100.0 * ok / max(1, len(records))
    lines.append('success %d/%d (%.0f %%): mission succeeded, every PAB succeeded, every mark due, the robot '
                 'within %.0f mm of the last point (truth)' % (ok, len(records), share, ARRIVE_MM))
    lines.append('s/m of the runs that succeeded, median / worst: %s' % _spread(per_m, '%.1f'))
    for leg in LEGS:
        errors = leg_errors(records, leg)
        lines.append('|estimate - truth| at the marks %s, median / worst: %s mm (%d marks)'
                     % ('in' if leg == 'in' else 'back', _spread(errors), len(errors)))
    return lines
