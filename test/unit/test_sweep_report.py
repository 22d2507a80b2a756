"""Sweep records as data: the table, two sweeps compared case by case, a
file cut short, seeds that do not depend on the other cases."""
import io

import pytest

import sweep_fake_bench as fake
from pirate.sweep import cases, records, report


def record(key, outcome, robot_s, group='90 mm straight', variant='', figures=None):
    return {'key': key, 'group': group, 'variant': variant, 'params': {}, 'seed': 1, 'outcome': outcome,
            'reason': 'why %s' % key, 'robot_s': robot_s, 'primitives': ['a', 'b'], 'truth': {},
            'figures': figures or {}}


A = [record('r=0', 'succeeded', 10.0), record('r=15', 'succeeded', 12.0), record('r=30', 'aborted', 5.0),
     record('left r=0', 'succeeded', 20.0, group='90 mm left')]


def test_the_table_counts_each_outcome_and_the_durations_of_the_successes():
    lines = report.table(A + [record('r=45', 'livelock', 30.0, figures={'error_mm': 4.0}),
                              record('r=60', 'succeeded', 14.0, figures={'error_mm': -2.0})])
    assert lines[0].split()[:8] == ['case', 'n', 'success', 'succeeded', 'FALSE', 'aborted', 'livelock', 'median']
    assert lines[1].split()[4:] == ['60%', '3', '0', '1', '1', '12.0', '/', '14.0', 's,', '2']
    assert lines[2] == '    error_mm 1 [-2, 4]'
    assert lines[3].startswith('90 mm left') and '20.0 / 20.0 s' in lines[3]


def test_two_sweeps_compared_flag_the_groups_and_cases_that_differ():
    b = [record('r=0', 'succeeded', 10.05), record('r=15', 'FALSE success', 12.0), record('r=30', 'aborted', 5.0),
         record('left r=0', 'succeeded', 30.0, group='90 mm left'),
         record('left r=45', 'succeeded', 1.0, group='90 mm left')]
    lines = report.compare(A, b)
    straight = next(line for line in lines if line.startswith('90 mm straight'))
    assert straight[36:].split()[:3] == ['3->3', '2->1', '0->1'] and straight.endswith('*')
    left = next(line for line in lines if line.startswith('90 mm left'))
    assert left[36:].split()[:2] == ['1->2', '1->2'] and left.endswith('*')
    assert '4 cases in both: 1 differ in outcome, 1 in duration only; 0 only in A, 1 only in B' in lines
    assert any(line.startswith('* r=15: succeeded -> FALSE success') for line in lines)
    assert any(line.startswith('  left r=0: succeeded, 20.0 s -> 30.0 s') for line in lines)
    assert not any(line.startswith('  r=0: succeeded, 10.0 s') for line in lines)     # within a Mega cycle


def test_the_same_sweep_twice_shows_no_difference():
    lines = report.compare(A, A)
    assert not any(line.endswith('*') for line in lines)
    assert '4 cases in both: 0 differ in outcome, 0 in duration only; 0 only in A, 0 only in B' in lines


def test_a_record_file_reads_back_and_a_last_line_cut_short_is_left_out(tmp_path):
    path = str(tmp_path / 's.jsonl')
    writer = records.Writer(path, records.header('fake', {'speedup': 10, 'mm': (90, 110)}, 3))
    writer.write(A[:2])
    writer.close()
    with open(path, 'a') as sink:
        sink.write('{"key": "r=3')
    head, found = records.read(path)
    assert head == {'name': 'fake', 'settings': {'speedup': 10, 'mm': [90, 110]}, 'seed': 3}
    assert found == A[:2] and records.finished(found) == {'r=0', 'r=15'}
    with open(path, 'a') as sink:
        sink.write('\n{}\n')
    with pytest.raises(ValueError):
        records.read(path)


def test_a_case_keeps_its_seed_whatever_the_other_cases_and_another_sweep_seed_draws_others():
    alone = fake.cases(['ok', 'ok', 'ok'])[2]
    among = fake.cases(['ok'] * 6)[2]
    assert alone['seed'] == among['seed']
    assert fake.cases(['ok'] * 3, seed=2)[2]['seed'] != alone['seed']
    assert len({one['seed'] for one in fake.cases(['ok'] * 50)}) == 50
    assert cases.seeds_line(fake.cases(['ok'] * 3), 1).startswith('sweep seed 1; case seeds drawn: ')


def test_a_case_result_with_a_field_the_records_do_not_have_is_refused():
    with pytest.raises(ValueError):
        records.complete(fake.cases(['ok'])[0], {'outcome': 'succeeded', 'seconds': 3}, {})
    with pytest.raises(ValueError):
        records.complete(fake.cases(['ok'])[0], {'reason': 'no outcome'}, {})


def test_the_report_command_prints_the_table_or_the_comparison(tmp_path):
    from importlib.machinery import SourceFileLoader
    import os
    bench = SourceFileLoader('sweep_report', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..',
                                                          'bench', 'sweep_report')).load_module()
    paths = []
    for name, found in (('a', A), ('b', A[:2])):
        paths.append(str(tmp_path / ('%s.jsonl' % name)))
        writer = records.Writer(paths[-1], records.header('fake', {}, 1))
        writer.write(found)
        writer.close()
    out = io.StringIO()
    assert bench.main([paths[0]], out) == 0
    assert '90 mm straight' in out.getvalue() and 'records' in out.getvalue()
    out = io.StringIO()
    assert bench.main(paths, out) == 0
    assert '0 only in B' in out.getvalue() and '2 only in A' in out.getvalue()
    assert bench.main([str(tmp_path / 'none.jsonl')], io.StringIO()) == 2


def test_the_table_keeps_the_order_the_sweep_declared_whatever_order_the_cases_finished_in():
    late, early = dict(record('b', 'succeeded', 3.0, group='second'), index=1), \
        dict(record('a', 'succeeded', 2.0, group='first'), index=0)
    lines = report.table([late, early])
    assert lines[1].startswith('first') and lines[2].startswith('second')


def test_by_robot_makes_a_row_per_drawn_robot_whatever_the_case():
    drawn = [dict(record('r=%d robot=%d' % (roll, robot), outcome, 10.0, group='%d mm' % mm), params={'robot': robot})
             for roll, robot, outcome, mm in ((0, 2, 'succeeded', 90), (15, 2, 'aborted', 110),
                                              (0, 1, 'succeeded', 110), (15, 1, 'succeeded', 90))]
    lines = report.table(report.by_robot(drawn + [record('r=0', 'aborted', 1.0)]))
    rows = [line.split()[:5] for line in lines[1:]]
    assert rows == [['nominal', 'twin', '1', '0%', '0'], ['robot', '1', '2', '100%', '2'],
                    ['robot', '2', '2', '50%', '1']]


def test_a_screen_keeps_the_robots_that_succeeded_in_all_of_it_and_the_nominal_twin():
    def on(robot, outcome):
        return dict(record('r robot=%s' % robot, outcome, 1.0), params={'robot': robot} if robot else {})
    screen = [on(1, 'succeeded'), on(1, 'succeeded'), on(2, 'succeeded'), on(2, 'aborted'), on(3, 'succeeded')]
    kept, passed = report.screened([on(1, 'aborted'), on(2, 'succeeded'), on(4, 'succeeded'), on(None, 'aborted')],
                                   screen)
    assert passed == [1, 3]
    assert [(r['params'].get('robot'), r['outcome']) for r in kept] == [(1, 'aborted'), (None, 'aborted')]


def test_reasons_count_each_failure_once_whatever_its_numbers():
    runs = [dict(record('r=%d' % k, outcome, 1.0), reason=why) for k, (outcome, why) in enumerate([
        ('aborted', 'bend_iv presses the wall at -0.62 rad, short of -0.68'), ('succeeded', 'fine'),
        ('aborted', 'bend_iv presses the wall at -0.64 rad, short of -0.68'), ('livelock', 'did not finish in 60')])]
    assert report.reasons_lines(runs) == ['90 mm straight',
                                          '    2 aborted: bend_iv presses the wall at # rad, short of #',
                                          '    1 livelock: did not finish in #']
