"""One real twin case through the sweep runner: a short Clamp Straight of
bench/pab_clamp_sweep, in a worker process of a local Dask cluster."""
import io
import os
from importlib.machinery import SourceFileLoader

from pirate.sweep import cli, records

BENCH = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'bench', 'pab_clamp_sweep')
CLAMP_SWEEP = SourceFileLoader('pab_clamp_sweep', BENCH).load_module()


def test_a_clamp_straight_runs_in_a_worker_and_is_judged_by_ground_truth(tmp_path):
    path = str(tmp_path / 'clamp.jsonl')
    args = CLAMP_SWEEP.parser().parse_args(['--diameters', '90', '--targets', 'straight', '--poses', 'straight',
                                            '--first', '90', '--step', '180', '--no-cancel', '--workers', '1',
                                            '--out', path])
    out = io.StringIO()
    assert cli.main(CLAMP_SWEEP.SWEEP, CLAMP_SWEEP.build, args, out) == 0, out.getvalue()
    _, found = records.read(path)
    assert len(found) == 1
    record = found[0]
    assert record['params'] == {'mm': 90, 'target': 'straight', 'pose': 'straight', 'roll_deg': 90, 'joints': None}
    assert record['outcome'] == 'succeeded' and record['truth']['verdict'] is True
    assert record['primitives'] == ['move front', 'clamp rear', 'clamp front']
    assert 5.0 < record['robot_s'] < 30.0
    assert record['mujoco'] and record['commit'] != 'unknown'
    assert '90 mm straight, straight, plain' in out.getvalue()


def test_drawn_robots_run_every_case_once_each_with_the_robot_in_its_key():
    args = CLAMP_SWEEP.parser().parse_args(['--diameters', '90', '--targets', 'straight', 'left', '--poses',
                                            'straight', '--first', '90', '--step', '180', '--robots', '3'])
    found, settings = CLAMP_SWEEP.build(args)
    assert sorted(c['key'] for c in found) == sorted(
        'mm=90 target=%s pose=straight roll_deg=90 robot=%d' % (target, k) for target in ('straight', 'left')
        for k in (1, 2, 3))
    assert settings['robots_seed'] == 1
