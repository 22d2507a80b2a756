"""Bad input to a sweep is a clear error before any case runs: an unknown
case parameter, a world that does not load, a scheduler that cannot be
reached, a records file that is not this sweep's."""
import argparse
import io
import os
import socket

import pytest

import sweep_fake_bench as fake
from pirate.sweep import cases, checks, cli, engine, records


def args_of(*argv):
    parser = argparse.ArgumentParser()
    cli.add_arguments(parser)
    return parser.parse_args(list(argv))


def ran_nothing(sweep, build, argv, capsys):
    """Run the sweep; assert it stopped on bad input; the error it printed."""
    out = io.StringIO()
    assert cli.main(sweep, build, args_of(*argv), out) == cli.BAD_INPUT
    assert out.getvalue() == ''
    return capsys.readouterr().err


def build(args):
    return fake.cases(['ok', 'ok']), {'marks': '/nonexistent'}


def test_an_unknown_case_parameter_is_named_with_those_the_bench_takes(tmp_path, capsys):
    err = ran_nothing(fake.SWEEP, build, ['--out', str(tmp_path / 'a.jsonl'), '--case', 'roll=30'], capsys)
    assert "unknown case parameter 'roll'" in err and 'n, behaviour' in err
    with pytest.raises(cases.SweepError, match='unknown case parameter'):
        cases.case(fake.SWEEP, {'n': 1, 'behaviour': 'ok', 'speed': 3}, 'g', 1)
    assert not os.path.exists(str(tmp_path / 'a.jsonl'))


def test_a_filter_no_case_matches_is_an_error(tmp_path, capsys):
    err = ran_nothing(fake.SWEEP, build, ['--out', str(tmp_path / 'a.jsonl'), '--case', 'n=7'], capsys)
    assert 'no case matches --case n=7' in err


def test_a_world_that_does_not_load_stops_the_sweep_before_its_first_case(tmp_path, capsys):
    bad = tmp_path / 'bent.yaml'
    bad.write_text('pieces: [{type: straight, length_mm: 100}, {type: bend}]\n')
    sweep = cases.Sweep('fake', fake.PARAMETERS, fake.run,
                        check=checks.world_check(lambda params, settings: str(bad) if params['n'] else 'straight_90'))
    err = ran_nothing(sweep, build, ['--out', str(tmp_path / 'a.jsonl')], capsys)
    assert 'world %s does not load' % bad in err
    assert checks.worlds(['straight_90', 'straight_110']) == []
    assert 'no_such_world' in checks.worlds(['no_such_world'])[0]


def test_a_scheduler_that_cannot_be_reached_is_said_before_any_case(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(engine, 'CONNECT_S', 1)
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        port = probe.getsockname()[1]
    address = 'tcp://127.0.0.1:%d' % port
    err = ran_nothing(fake.SWEEP, build, ['--out', str(tmp_path / 'a.jsonl'), '--scheduler', address], capsys)
    assert 'cannot reach the Dask scheduler at %s' % address in err


def test_a_records_file_is_not_overwritten_and_resumed_only_with_the_same_options(tmp_path, capsys):
    path = str(tmp_path / 'a.jsonl')
    writer = records.Writer(path, records.header('fake', {'marks': '/elsewhere'}, 1))
    writer.close()
    assert 'exists: --resume to continue it' in ran_nothing(fake.SWEEP, build, ['--out', path], capsys)
    err = ran_nothing(fake.SWEEP, build, ['--out', path, '--resume'], capsys)
    assert 'resume it with the same options' in err and '/elsewhere' in err
    err = ran_nothing(fake.SWEEP, build, ['--out', str(tmp_path / 'none.jsonl'), '--resume'], capsys)
    assert '--resume needs --out FILE of an earlier sweep' in err
