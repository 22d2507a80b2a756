#!/usr/bin/env python3
"""Load for the rostests: keep cores busy until killed (roslaunch ends it).

One process by default (the trace rostest: primitives can go missing from
the feedback on a loaded machine; the trace in the result must not).
``--per-core N``: N processes per core of this machine instead
(the busy-machine rostest: a laptop running RViz, a bag and a video
grabber). Pure CPU, no ROS traffic; each process ends when its parent does.
"""
import argparse
import multiprocessing
import os
import time

#: Wall s a load process runs at most: a safety net if the launch forgets it.
SAFETY_S = 600.0


def burn(parent):
    """Spin on the CPU until ``SAFETY_S`` passed or the process ``parent`` is gone."""
    end = time.monotonic() + SAFETY_S
    while time.monotonic() < end and os.getppid() == parent:
        sum(i * i for i in range(10000))


def processes(per_core):
    """How many load processes: ``per_core`` x the cores, or one when ``per_core`` is 0."""
    return per_core * multiprocessing.cpu_count() if per_core > 0 else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--per-core', type=int, default=0, help='processes per core (0: one process)')
    count = processes(parser.parse_known_args()[0].per_core)     # roslaunch adds __name:= and __log:=
    print('busy_loop: %d processes on %d cores' % (count, multiprocessing.cpu_count()), flush=True)
    me = os.getpid()
    workers = [multiprocessing.Process(target=burn, args=(me,), daemon=True) for _ in range(count - 1)]
    for worker in workers:
        worker.start()
    burn(os.getppid())


if __name__ == '__main__':
    main()
