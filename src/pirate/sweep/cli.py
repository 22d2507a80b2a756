"""What every sweep bench's command line shares: ``--workers``,
``--scheduler``, ``--out``, ``--resume``, ``--case``, ``--time-limit``,
``--seed``; and :func:`main`, which checks everything before the first
case runs, runs the sweep and prints its table."""
import os
import sys
import time

from pirate.sweep import cases as sweep_cases
from pirate.sweep import engine as engines
from pirate.sweep import records, report, runner
from pirate.sweep.child import provenance
from pirate.sweep.progress import Progress, clock_text

#: Exit status of bad input (nothing ran) and of a sweep stopped by Ctrl-C (records kept).
BAD_INPUT, STOPPED = 2, 130


def add_arguments(parser, seed=1):
    """The runner's options on a bench's ``parser``."""
    group = parser.add_argument_group('sweep runner (doc/sweeps.md)')
    group.add_argument('--workers', type=int, default=None,
                       help='worker processes of the local Dask cluster (default: every core); '
                            '0: one case after the other without Dask')
    group.add_argument('--scheduler', metavar='tcp://HOST:PORT', help='run on this Dask scheduler instead')
    group.add_argument('--out', help='records file, JSON Lines (default: sweeps/<bench>_<UTC time>.jsonl)')
    group.add_argument('--resume', action='store_true', help='continue --out: skip the cases it has records of')
    group.add_argument('--case', nargs='+', action='extend',
                       default=[], metavar='NAME=VALUE', help='only the cases with these parameters')
    group.add_argument('--time-limit', type=float, metavar='S',
                       help='wall s a case may run before it counts as hung (default: the bench\'s)')
    group.add_argument('--seed', type=int, default=seed, help='the sweep seed the case seeds are drawn from')


def main(sweep, build, args, stream=sys.stdout):
    """Build the cases (``build(args)`` -> (cases, settings)), run them and
    print the table; the exit status (0, :data:`BAD_INPUT`, :data:`STOPPED`)."""
    try:
        todo, settings, path, head, done = prepare(sweep, build, args)
        engine = make_engine(sweep, args, settings)
    except (sweep_cases.SweepError, ValueError, OSError) as bad:
        sys.stderr.write('%s: %s\n' % (sweep.name, bad))
        return BAD_INPUT
    stream.write('%s: %d cases%s, %s; records: %s\n' % (
        sweep.name, len(todo) + len(records.finished(done)),
        ' (%d done before, skipped)' % len(records.finished(done)) if done else '',
        where(args, engine), path))
    stream.write(sweep_cases.seeds_line(todo, args.seed) + '\n')
    stream.flush()
    return execute(sweep, todo, engine, path, head, done, stream)


def where(args, engine):
    """Where the cases run, as the first line says it."""
    if args.scheduler:
        workers = engine.workers()
        return 'on %s, %s' % (args.scheduler, '%d workers' % workers if workers
                              else 'no worker yet: the cases wait for one')
    return 'one after the other' if args.workers == 0 else '%d local worker processes' % engine.workers()


def execute(sweep, todo, engine, path, head, done, stream):
    """Run ``todo`` on ``engine`` into ``path`` (``done``: the records of cases
    finished before); Ctrl-C stops the workers and keeps the records."""
    writer = records.Writer(path, head)
    progress = Progress(len(todo) + len({r['key'] for r in done}), stream, stream.isatty(), done)
    started = time.monotonic()
    try:
        lost = runner.run(todo, engine, writer.write, progress, provenance())
    except KeyboardInterrupt:
        progress.end()
        stream.write('stopped: the records so far are in %s; continue with --resume --out %s\n' % (path, path))
        return STOPPED
    finally:
        engine.close()
        writer.close()
    found = records.read(path)[1]
    stream.write('\n'.join(report.table(found) + sweep.summary(found)) + '\n')
    lost_text = ', %d crashed or hung' % lost if lost else ''
    stream.write('%d cases in %s wall%s; records: %s\n'
                 % (len(todo), clock_text(time.monotonic() - started), lost_text, path))
    return 0


def prepare(sweep, build, args):
    """(cases to run, settings, records path, header to write or None, records of the cases done before);
    raises on bad input."""
    filters = sweep_cases.parse_filters(args.case, sweep)
    every, settings = build(args)
    every = [dict(one, index=index) for index, one in enumerate(sweep_cases.unique(every))]
    chosen = sweep_cases.select(every, filters)
    if not chosen:
        raise sweep_cases.SweepError('no case matches --case %s' % ' '.join(args.case))
    errors = sweep.check(chosen, settings)
    if errors:
        raise sweep_cases.SweepError('; '.join(errors))
    stamp = time.strftime('%Y%m%d-%H%M%S', time.gmtime())
    path = args.out or os.path.join('sweeps', '%s_%s.jsonl' % (sweep.name, stamp))
    head = records.header(sweep.name, settings, args.seed)
    if args.resume:
        return _resumed(chosen, settings, path, head, args)
    if os.path.exists(path):
        raise sweep_cases.SweepError('%s exists: --resume to continue it, or another --out' % path)
    return chosen, settings, path, head, []


def _resumed(chosen, settings, path, head, args):
    if not args.out or not os.path.exists(path):
        raise sweep_cases.SweepError('--resume needs --out FILE of an earlier sweep')
    before, found = records.read(path)
    if before != head['sweep']:
        raise sweep_cases.SweepError('%s was written by %s with %s; these options give %s: resume it with the '
                                     'same options' % (path, (before or {}).get('name'), before, head['sweep']))
    done = records.finished(found)
    return [one for one in chosen if one['key'] not in done], settings, path, None, found


def make_engine(sweep, args, settings):
    """The engine the options ask for; raises :class:`SweepError` when it cannot start."""
    module = sys.modules[sweep.run.__module__]
    bench_path = os.path.abspath(module.__file__)
    limit = args.time_limit or sweep.time_limit_s
    if args.workers is not None and args.workers < 0:
        raise sweep_cases.SweepError('--workers %d: 0 or more' % args.workers)
    if args.workers == 0 and not args.scheduler:
        return engines.Serial(bench_path, sweep.run.__name__, settings, limit)
    return engines.Dask(bench_path, sweep.run.__name__, settings, limit, workers=args.workers,
                        scheduler=args.scheduler)
