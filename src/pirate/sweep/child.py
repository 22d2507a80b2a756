"""One case in a process of its own: the runner's process edge.

:func:`run_case` (what a worker runs) starts ``python3 -m
pirate.sweep.child BENCH FUNCTION RESULT`` with the case and the settings on
stdin; the child loads the bench file, calls the case function and writes
the records as JSON to RESULT. MuJoCo, the in-process server and anything a
bench changes in its process die with the case. A child that raises,
crashes or outlives the time limit (killed) gives no records, only why.
"""
import ctypes
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import traceback
from importlib.machinery import SourceFileLoader

from pirate.sweep import records

PR_SET_PDEATHSIG = 1


def run_case(bench_path, function, case, settings, time_limit_s):
    """Run ``case`` in a child process: ('ok', [record, ...]) or ('crashed' |
    'hang', reason). Blocks at most ``time_limit_s`` wall seconds (plus the kill)."""
    with tempfile.TemporaryDirectory(prefix='sweep_case_') as scratch:
        result_path = os.path.join(scratch, 'result.json')
        started = time.monotonic()
        child = subprocess.Popen([sys.executable, '-m', 'pirate.sweep.child', bench_path, function, result_path],
                                 stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                 env=_child_env(), start_new_session=True)
        try:
            _, err = child.communicate(json.dumps({'case': case, 'settings': settings}).encode('utf-8'),
                                       timeout=time_limit_s)
        except subprocess.TimeoutExpired:
            return 'hang', 'no records within %g s wall (the case was killed)' % time_limit_s
        finally:
            if child.poll() is None:
                os.killpg(child.pid, signal.SIGKILL)
                child.wait()
        if child.returncode != 0 or not os.path.exists(result_path):
            return 'crashed', _last_words(child.returncode, err)
        with open(result_path) as source:
            found = json.load(source)
        wall_s, worker = time.monotonic() - started, _worker()
        for record in found:
            record.update(wall_s=round(wall_s, 1), worker=worker)
        return 'ok', found


def _worker():
    """The address of the Dask worker running this, or None (no Dask)."""
    try:
        from distributed import get_worker
        return get_worker().address
    except (ImportError, ValueError):
        return None


def _child_env():
    """This process's environment, with the pirate package first on the child's path."""
    env = dict(os.environ)
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env['PYTHONPATH'] = os.pathsep.join([here] + [p for p in env.get('PYTHONPATH', '').split(os.pathsep) if p])
    return env


def _last_words(code, err):
    lines = [line for line in err.decode('utf-8', 'replace').splitlines() if line.strip()]
    said = lines[-1].strip() if lines else 'nothing on stderr'
    how = 'killed by signal %d' % -code if code < 0 else 'exit status %d' % code
    return '%s: %s' % (how, said[:300])


def provenance():
    """The code's commit and the MuJoCo version of this process, and where it runs."""
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        commit = subprocess.check_output(['git', '-C', here, 'describe', '--always', '--dirty', '--abbrev=12'],
                                         stderr=subprocess.DEVNULL).decode().strip()
    except (OSError, subprocess.CalledProcessError):
        commit = 'unknown'
    try:
        import mujoco
        engine = mujoco.__version__
    except ImportError:
        engine = None
    return {'commit': commit, 'mujoco': engine, 'host': socket.gethostname()}


def _die_with_parent():
    """Linux: this process ends when the worker that started it does (Ctrl-C, a killed worker)."""
    try:
        ctypes.CDLL(None).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except (OSError, AttributeError):
        pass


def here(bench_path):
    """``bench_path``, or where this machine's checkout has that bench (a worker on another machine)."""
    if os.path.exists(bench_path):
        return bench_path
    top = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    return os.path.join(top, 'bench', os.path.basename(bench_path))


def main(argv=None):
    bench_path, function, result_path = (argv or sys.argv[1:])[:3]
    _die_with_parent()
    given = json.load(sys.stdin)
    case = given['case']
    sys.stdout = sys.stderr         # a bench's prints are not the result
    bench = SourceFileLoader('sweep_bench', here(bench_path)).load_module()
    try:
        results = getattr(bench, function)(case['params'], case['seed'], given['settings'])
    except Exception:       # noqa: BLE001 - the runner records it (after one retry)
        traceback.print_exc()
        return 1
    found = provenance()
    done = [records.complete(case, result, dict(found, attempts=1))
            for result in (results if isinstance(results, list) else [results])]
    with open(result_path + '.part', 'w') as sink:
        json.dump(done, sink)
    os.rename(result_path + '.part', result_path)
    return 0


if __name__ == '__main__':
    sys.exit(main())
