"""Checks a twin bench runs on its cases before the first one runs."""
from pirate.world import network


def worlds(names):
    """Errors of the worlds ``names`` (names or paths; None: a case that runs no world) that do not load,
    one string each."""
    errors = []
    for name in sorted(set(names) - {None}):
        try:
            network.load(network.world_path(name))
        except network.WorldError as bad:
            errors.append('world %s does not load: %s' % (name, bad))
    return errors


def world_check(world_of):
    """A :class:`pirate.sweep.cases.Sweep` check: every case's world
    (``world_of(params, settings)``) loads."""
    return lambda cases, settings: worlds(world_of(one['params'], settings) for one in cases)
