"""Which simulated robot stands behind the node and the harness: the
physics twin (:class:`pirate.sim.twin.TwinRobot`) in a pipe network.

The world is a file or a name under config/worlds/; without one, the
straight pipe of the given diameter (``straight_90`` / ``straight_110``).
There is no other simulated robot: the fitted fast fake
(:mod:`pirate.sim.fake_robot`) is built explicitly by the unit tests that
need it, never chosen here.
"""
from pirate.world.network import world_path

#: Pipe diameters (mm) with a straight world of their own.
STRAIGHT_WORLDS = {90: 'straight_90', 110: 'straight_110'}


def default_world(pipe_diameter):
    """The straight pipe of ``pipe_diameter`` mm (90 or 110)."""
    try:
        return STRAIGHT_WORLDS[int(pipe_diameter)]
    except (KeyError, ValueError):
        raise ValueError('pipe_diameter %r: only %s mm have a straight world'
                         % (pipe_diameter, ' and '.join(str(d) for d in sorted(STRAIGHT_WORLDS))))


def of_node(get_param, logfatal):
    """The robot a node's private params name (``sim_robot``, ``fil_robot``):
    ``~world``, ``~pipe_diameter``, ``~orientation`` (rad), ``~joints``
    (start angles, :mod:`pirate.sim.twin_start`), ``~seed`` (-1: no noise).
    A bad one is logged fatal with its reason and ends the node
    (SystemExit 1) before it publishes anything: a robot that is not the one
    asked for must not start."""
    try:
        return make_robot(world=get_param('~world', ''), pipe_diameter=get_param('~pipe_diameter', 90),
                          orientation=float(get_param('~orientation', 1.5707963)), joints=get_param('~joints', {}),
                          seed=int(get_param('~seed', -1)))     # the twin takes a negative seed as no noise
    except ValueError as refused:      # WorldError, StartPoseError, a diameter without a world, not a number
        logfatal('cannot start the simulated robot: %s' % refused)
        raise SystemExit(1)


def make_robot(world='', pipe_diameter=90, orientation=1.5707963, joints=None, seed=None, config=None):
    """The physics twin in ``world`` (default: the straight pipe of
    ``pipe_diameter`` mm); ``config``: its constants, default config/twin.yaml."""
    from pirate.sim.twin import TwinRobot      # MuJoCo is imported only when a robot is built
    return TwinRobot(world_path(world or default_world(pipe_diameter)), orientation=orientation,
                     joints=joints, seed=seed, config=config)
