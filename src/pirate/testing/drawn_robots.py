"""Drawn robots: a sweep's cases on robots drawn from the twin's plausible ranges.

``--robots N`` runs every case of a bench on N robots instead of the
nominal twin. Robot ``k`` is config/twin.yaml with every constant that has
a plausible range in config/twin_sources.yaml drawn uniformly from it
(:func:`pirate.sim.twin_sources.drawn`), from the sweep seed and ``k``
alone, with its sensors' noise and offsets on (the case's seed). A case's
``robot`` parameter is ``k``: ``--case robot=3`` runs robot 3 again, and
``bench/twin_robots`` prints what it was drawn.
"""
from pirate.sim import twin_sources
from pirate.sweep.cases import SweepError, case, seed_of


def add_arguments(parser):
    """``--robots`` on a bench's ``parser``."""
    parser.add_argument('--robots', type=int, default=0, metavar='N',
                        help="every case on N robots drawn from the twin constants' plausible ranges "
                             '(doc/sweeps.md#drawn-robots); 0: the nominal twin')


def over(found, sweep, args):
    """``found`` cases once per drawn robot (parameter ``robot`` 1..N, the
    group marked), or unchanged without ``--robots``; ``sweep`` must take a
    ``robot`` parameter."""
    if args.robots < 0:
        raise SweepError('--robots %d: 0 or more' % args.robots)
    if not args.robots:
        return found
    return [case(sweep, dict(one['params'], robot=number), one['group'] + ', drawn robots', args.seed)
            for one in found for number in range(1, args.robots + 1)]


def settings(args):
    """What a case needs to draw its robot again (the bench's settings)."""
    return {'robots_seed': args.seed}


def robot_seed(sweep_seed, number):
    """The draw seed of robot ``number`` of the sweep seeded ``sweep_seed``."""
    return seed_of(sweep_seed, 'robot %d' % number)


def constants(sweep_seed, number):
    """({'section.key': value} drawn, the whole config) of robot ``number``."""
    config, changes = twin_sources.drawn(robot_seed(sweep_seed, number))
    return changes, config


def twin_args(params, seed, bench_settings):
    """SimHarness keyword arguments for the case's robot: none for the
    nominal twin; for a drawn robot its constants and the case ``seed`` (its
    sensors' noise and offsets)."""
    number = params.get('robot')
    if number is None:
        return {}
    return {'config': constants(bench_settings['robots_seed'], number)[1], 'seed': seed}
