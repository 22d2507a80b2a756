"""Where the cases run: on a Dask cluster (the default: a local one, one
single-threaded worker process per core; or the lab's, ``--scheduler
tcp://HOST:PORT``), or one after the other in this process
(:class:`Serial`, ``--workers 0``). Either way each case runs in a child
process of its own (:func:`pirate.sweep.child.run_case`).

Written to the API old Dask releases share (Ubuntu 20.04's python3-
distributed as well as Debian 12's): ``LocalCluster(n_workers,
threads_per_worker, processes)``, ``Client``, ``as_completed``.
"""
import collections
import os
import signal
import threading

from pirate.sweep.cases import SweepError
from pirate.sweep.child import run_case

#: Wall seconds to reach a scheduler given with ``--scheduler``.
CONNECT_S = 10


def _deaf_to_ctrl_c(start):
    """``start()`` with Ctrl-C ignored by the processes it starts (they inherit it):
    a Ctrl-C stops the sweep here, which then closes the workers in order."""
    if threading.current_thread() is not threading.main_thread():
        return start()
    before = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        return start()
    finally:
        signal.signal(signal.SIGINT, before)


class Serial(object):
    """Cases one after the other, each in a child process: the reference the parallel runs must equal."""

    def __init__(self, bench_path, function, settings, time_limit_s):
        self._task = (bench_path, function, settings, time_limit_s)
        self._queue = collections.deque()

    def submit(self, case):
        self._queue.append(case)

    def results(self):
        bench_path, function, settings, time_limit_s = self._task
        while self._queue:
            case = self._queue.popleft()
            status, payload = run_case(bench_path, function, case, settings, time_limit_s)
            yield case, status, payload

    def workers(self):
        return 1

    def close(self):
        self._queue.clear()


class Dask(object):
    """Cases as Dask tasks: ``scheduler`` (an address) or a local cluster of ``workers`` processes."""

    def __init__(self, bench_path, function, settings, time_limit_s, workers=None, scheduler=None):
        from distributed import Client, LocalCluster, as_completed
        self._task = (bench_path, function, settings, time_limit_s)
        self._cluster = None
        if scheduler:
            try:
                self.client = Client(scheduler, timeout=CONNECT_S)
            except Exception as unreachable:    # noqa: BLE001 - OSError, TimeoutError: Dask's differ by release
                raise SweepError('cannot reach the Dask scheduler at %s: %s' % (scheduler, unreachable))
        else:
            self._cluster = _deaf_to_ctrl_c(lambda: LocalCluster(
                n_workers=workers or os.cpu_count(), threads_per_worker=1, processes=True, dashboard_address=None))
            self.client = Client(self._cluster)
        self._cases, self._futures, self._all = {}, as_completed([]), []

    def workers(self):
        return len(self.client.scheduler_info().get('workers', {}))

    def submit(self, case):
        bench_path, function, settings, time_limit_s = self._task
        future = self.client.submit(run_case, bench_path, function, case, settings, time_limit_s, pure=False)
        self._cases[future.key] = case
        self._all.append(future)
        self._futures.add(future)

    def results(self):
        for future in self._futures:
            case = self._cases.pop(future.key)
            try:
                status, payload = future.result()
            except Exception as lost:       # noqa: BLE001 - the worker died under the case
                status, payload = 'crashed', 'worker lost: %s' % lost
            yield case, status, payload

    def close(self):
        """Stop every worker (a Ctrl-C lands here: running cases die with them)."""
        self.client.cancel([future for future in self._all if not future.done()])
        self.client.close()
        if self._cluster is not None:
            self._cluster.close()
