"""How bench/mission_sweep --job judges a run of an inspection job and sums
its runs (pirate.testing.job_run): marks fall due as the job node decides,
each against the truth at that moment; no twin."""
import os
import subprocess
import sys

from pirate.inspection import job as jobs
from pirate.inspection.job import Mark
from pirate.testing import job_run

BENCH = os.path.join(os.path.dirname(__file__), '..', '..', 'bench', 'mission_sweep')

IN_800, IN_1790, BACK_2190 = (Mark(800.0, 'in', 'leak', ''), Mark(1790.0, 'in', 'corrosion', ''),
                              Mark(2190.0, 'back', 'water', ''))


class Twin(object):
    """An estimate and a truth the test moves."""
    def __init__(self):
        self.estimate_mm, self.truth_mm, self.truth_reads = None, 0.0, 0

    def truth(self):
        self.truth_reads += 1
        return self.truth_mm


def watched(marks):
    twin = Twin()
    return twin, job_run.MarkWatch(jobs.DueMarks(marks), lambda: twin.estimate_mm, twin.truth)


def go(twin, watch, estimate_mm, truth_mm):
    """One robot cycle: the estimate and truth move, the watch checks and records as the harness would."""
    twin.estimate_mm, twin.truth_mm = estimate_mm, truth_mm
    if watch.check():
        watch.record()


def test_a_mark_is_seen_with_the_estimate_that_made_it_due_and_the_truth_then():
    twin, watch = watched([IN_800, IN_1790])
    assert not watch.check()                # nothing reported yet
    for estimate, truth in ((400.0, 400.0), (790.0, 780.0), (805.0, 795.0), (900.0, 893.0)):
        go(twin, watch, estimate, truth)
    assert watch.seen == [job_run.Seen(IN_800, 805.0, 795.0, None)]
    assert twin.truth_reads == 1 and watch.left() == [IN_1790]
    assert job_run.mark_figures(watch.seen) == {'mark_in_800_mm': 10.0}


def test_a_back_mark_waits_for_the_first_step_taken_rear_first_and_a_jump_passes_it():
    twin, watch = watched([BACK_2190])
    for estimate in (2100.0, 2300.0, 2995.0):          # on the way in it is not due
        go(twin, watch, estimate, estimate)
    watch.step(-205.0, 8)
    go(twin, watch, 2250.0, 2240.0)
    go(twin, watch, 2140.0, 2200.0)                    # a re-anchoring jump over it
    assert watch.seen == [job_run.Seen(BACK_2190, 2140.0, 2200.0, 8)] and watch.left() == []
    assert job_run.mark_figures(watch.seen) == {'mark_back_2190_mm': -60.0, 'step_of_mark_back_2190_mm': 8}


def test_a_run_succeeds_only_back_within_the_tolerance_with_every_pab_and_mark():
    ok = ['succeeded'] * 3
    assert job_run.judge('succeeded', ok, 12.0, []) == ('succeeded', '')
    assert job_run.judge('succeeded', ok, -job_run.ARRIVE_MM - 1, [])[0] == 'FALSE success'
    assert job_run.judge('succeeded', ok, 0.0, [IN_800])[0] == 'marks missed'
    assert job_run.judge('succeeded', ['aborted'] + ok, 0.0, [])[0] == 'retried'
    assert job_run.judge('aborted', ok, 0.0, []) == ('aborted', '')


def record(n, outcome, s_per_m, marks):
    figures = dict(marks, s_per_m=s_per_m, arrive_err_mm=-8.0, start_roll_rad=1.5708, marks_due=len(marks))
    return {'key': 'run=%d' % n, 'index': n - 1, 'seed': 100 + n, 'outcome': outcome, 'reason': 'why',
            'figures': figures}


def test_the_summary_gives_every_run_then_success_s_per_m_and_the_errors_in_and_back():
    first = {'mark_in_800_mm': 10.0, 'mark_back_2190_mm': -30.0, 'step_of_mark_back_2190_mm': 9}
    found = [record(1, 'succeeded', 40.0, first),
             record(2, 'retried', 50.0, {'mark_in_800_mm': -20.0, 'mark_in_1790_mm': 4.0}),
             record(3, 'succeeded', 42.0, {'mark_in_800_mm': 6.0, 'mark_back_2190_mm': 70.0})]
    lines = job_run.summary_lines(found)
    assert lines[0].startswith('run=1 seed 101 roll 90.0 deg: succeeded; 40.0 s/m; end -8 mm')
    assert 'in_800 +10, back_2190 -30 (step 9)' in lines[0] and 'retried (why)' in lines[1]
    assert 'in_800 -20, in_1790 +4' in lines[1]
    assert lines[3].startswith('success 2/3 (67 %)')
    assert lines[4].endswith('41.0 / 42.0')
    assert lines[5].endswith('in, median / worst: 8 / 20 mm (4 marks)')
    assert lines[6].endswith('back, median / worst: 50 / 70 mm (2 marks)')


def test_a_job_the_bench_cannot_run_is_an_error_before_any_run(tmp_path):
    bad = tmp_path / 'job.yaml'
    bad.write_text('map: inspection_network_90\nroute: [launch_pit]\n')
    for extra, said in (([str(bad)], 'route: the names of two points or more'),
                        (['config/jobs/inspection_demo.yaml', '--to', 'target'], '--job names the map')):
        done = subprocess.run([sys.executable, BENCH, '--workers', '0', '--out', str(tmp_path / 'r.jsonl'), '--job']
                              + extra, cwd=os.path.join(os.path.dirname(BENCH), '..'), stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, universal_newlines=True, timeout=120)
        assert done.returncode == 2 and said in done.stderr, done.stderr
        assert not (tmp_path / 'r.jsonl').exists()
