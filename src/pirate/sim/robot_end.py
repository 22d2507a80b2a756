"""Which simulated robot stands behind the node and the harness.

With a world file: the physics twin in that pipe network
(:class:`pirate.sim.twin.TwinRobot`). Without one: the fitted single
cross-section model (:class:`pirate.sim.model.PirateModel`). Both take the
three arrays and give raw Small States, so nothing else changes.
"""
import os

from pirate import paths

WORLDS_DIR = os.path.join(paths.CONFIG_DIR, 'worlds')


def world_path(world):
    """A world file: a path, or a name under config/worlds/ ('straight_90')."""
    if os.path.sep in world or world.endswith('.yaml'):
        return world
    return os.path.join(WORLDS_DIR, world + '.yaml')


def make_robot(world='', pipe_diameter=90, orientation=1.5707963, joints=None, seed=None, config=None):
    """The robot end: the twin in ``world`` if given (``config``: its
    constants, default config/twin.yaml), else the fitted model."""
    if world:
        from pirate.sim.twin import TwinRobot      # MuJoCo only when a world asks for it
        return TwinRobot(world_path(world), orientation=orientation, joints=joints, seed=seed, config=config)
    from pirate.sim.model import PirateModel
    return PirateModel(pipe_diameter=pipe_diameter, orientation=orientation, joints=joints, seed=seed)
