"""The sweep runner on a fake case function: serial and on a local Dask
cluster alike, a crashed or hung case retried once then recorded, resume,
and Ctrl-C keeping the records written so far."""
import argparse
import io
import os

import pytest

import sweep_fake_bench as fake
from pirate.sweep import cli, engine, records, runner
from pirate.sweep.cases import Sweep
from pirate.sweep.progress import Progress

BENCH = fake.__file__


def quiet():
    return Progress(0, io.StringIO(), False)


def run_serial(cases, settings, path, limit_s=30.0):
    writer = records.Writer(path)
    lost = runner.run(cases, engine.Serial(BENCH, 'run', settings, limit_s), writer.write, quiet(), {})
    writer.close()
    return lost, records.read(path)[1]


def by_key(found):
    return {(r['key'], r['variant']): records.comparable(r) for r in found}


def test_every_case_gives_its_records_with_seed_commit_and_engine(tmp_path):
    settings = {'marks': str(tmp_path), 'variants': 2}
    lost, found = run_serial(fake.cases(['ok'] * 3), settings, str(tmp_path / 'a.jsonl'))
    assert lost == 0
    assert len(found) == 6
    first = found[0]
    assert first['params'] == {'n': 0, 'behaviour': 'ok'} and first['seed'] == fake.cases(['ok'])[0]['seed']
    assert first['commit'] and 'mujoco' in first and first['attempts'] == 1
    assert {r['variant'] for r in found} == {'', 'again'}


def test_a_crashing_case_runs_once_more_then_is_recorded_as_crashed(tmp_path):
    settings = {'marks': str(tmp_path)}
    lost, found = run_serial(fake.cases(['crash', 'crash once', 'raise', 'ok']), settings,
                             str(tmp_path / 'a.jsonl'))
    outcome = {r['params']['behaviour']: r for r in found}
    assert lost == 2
    assert outcome['crash']['outcome'] == 'crashed' and outcome['crash']['attempts'] == 2
    assert 'signal 6' in outcome['crash']['reason']
    assert outcome['raise']['outcome'] == 'crashed' and 'went wrong' in outcome['raise']['reason']
    assert outcome['crash once']['outcome'] != 'crashed' and outcome['crash once']['attempts'] == 2
    assert outcome['ok']['attempts'] == 1


def test_a_hung_case_is_killed_at_the_time_limit_and_recorded(tmp_path):
    lost, found = run_serial(fake.cases(['hang']), {'marks': str(tmp_path)}, str(tmp_path / 'a.jsonl'),
                             limit_s=1.0)
    assert lost == 1
    assert found[0]['outcome'] == 'hang' and found[0]['attempts'] == 2


def test_the_same_seed_and_code_give_the_same_records_in_parallel_as_one_after_the_other(tmp_path):
    behaviours = ['ok', 'slow', 'ok', 'slow', 'ok']
    settings = {'marks': str(tmp_path / 'serial'), 'slow_s': 0.3}
    os.makedirs(settings['marks'])
    _, serial = run_serial(fake.cases(behaviours), settings, str(tmp_path / 'serial.jsonl'))
    os.makedirs(str(tmp_path / 'parallel'))
    settings['marks'] = str(tmp_path / 'parallel')
    dask = engine.Dask(BENCH, 'run', settings, 30.0, workers=2)
    writer = records.Writer(str(tmp_path / 'parallel.jsonl'))
    try:
        assert dask.workers() == 2
        runner.run(fake.cases(behaviours), dask, writer.write, quiet(), {})
    finally:
        dask.close()
        writer.close()
    parallel = records.read(str(tmp_path / 'parallel.jsonl'))[1]
    assert by_key(parallel) == by_key(serial)
    assert all(r['worker'].startswith('tcp://') for r in parallel) and all(r['worker'] is None for r in serial)


class Interrupted(engine.Serial):
    """Ctrl-C after ``after`` cases have finished."""

    def __init__(self, after, *args):
        engine.Serial.__init__(self, *args)
        self.after = after

    def results(self):
        for number, result in enumerate(engine.Serial.results(self)):
            if number == self.after:
                raise KeyboardInterrupt
            yield result


def sweep_args(path, *extra):
    parser = argparse.ArgumentParser()
    cli.add_arguments(parser)
    return parser.parse_args(['--out', path, '--workers', '0'] + list(extra))


def build(behaviours):
    return lambda args: (fake.cases(behaviours, args.seed), {'marks': os.path.dirname(args.out)})


def test_ctrl_c_keeps_the_records_so_far_and_resume_runs_only_the_rest(tmp_path, monkeypatch):
    path = str(tmp_path / 'sweep.jsonl')
    behaviours = ['ok'] * 5
    monkeypatch.setattr(cli, 'make_engine',
                        lambda sweep, args, settings: Interrupted(2, BENCH, 'run', settings, 30.0))
    out = io.StringIO()
    assert cli.main(fake.SWEEP, build(behaviours), sweep_args(path), out) == cli.STOPPED
    head, kept = records.read(path)
    assert head['name'] == 'fake' and [r['params']['n'] for r in kept] == [0, 1]
    assert 'resume' in out.getvalue()
    monkeypatch.setattr(cli, 'make_engine', lambda sweep, args, settings: engine.Serial(BENCH, 'run', settings, 30.0))
    out = io.StringIO()
    assert cli.main(fake.SWEEP, build(behaviours), sweep_args(path, '--resume'), out) == 0
    assert '(2 done before, skipped)' in out.getvalue()
    assert '3/5 cases, success 3/3 runs' in out.getvalue()      # the records of before count
    _, found = records.read(path)
    assert sorted(r['params']['n'] for r in found) == [0, 1, 2, 3, 4]
    assert 'fake even' in out.getvalue()       # the table, from the records


def test_the_progress_line_is_rewritten_on_a_terminal_and_plain_otherwise():
    for tty in (True, False):
        stream = io.StringIO()
        progress = Progress(2, stream, tty, clock=iter([0.0, 10.0, 20.0]).__next__)
        progress.finished([{'key': 'n=0', 'variant': '', 'outcome': 'succeeded'}])
        progress.finished([{'key': 'n=1', 'variant': '', 'outcome': 'hang'}])
        progress.end()
        text = stream.getvalue()
        assert '1/2 cases, success 1/1 runs, 10 s left' in text
        assert '2/2 cases, success 1/2 runs, 0 s left' in text
        assert (text.count('\r') == 2) == tty and text.count('\n') == (1 if tty else 2)


if __name__ == '__main__':
    pytest.main([__file__])


def test_a_bench_summary_is_printed_under_the_table_from_the_records(tmp_path):
    path = str(tmp_path / 'sweep.jsonl')
    summed = Sweep('fake', fake.PARAMETERS, fake.run, summary=lambda found: ['%d runs summed' % len(found)])
    out = io.StringIO()
    assert cli.main(summed, build(['ok'] * 3), sweep_args(path), out) == 0
    text = out.getvalue()
    assert text.index('fake even') < text.index('3 runs summed')
