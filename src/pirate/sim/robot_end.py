"""Which simulated robot stands behind the node and the harness.

With a world file: the physics twin in that pipe network
(:class:`pirate.sim.twin.TwinRobot`). Without one: the fitted single
cross-section model (:class:`pirate.sim.fake_robot.FakeRobot`). Both take the
three arrays and give raw Small States, so nothing else changes.
"""
from pirate.world.network import world_path

#: The launch files' word for "no world: the fitted model".
NO_WORLD = 'none'


def make_robot(world='', pipe_diameter=90, orientation=1.5707963, joints=None, seed=None, config=None):
    """The robot end: the twin in ``world`` if given (``config``: its
    constants, default config/twin.yaml), else the fitted model."""
    if world and world != NO_WORLD:
        from pirate.sim.twin import TwinRobot      # MuJoCo only when a world asks for it
        return TwinRobot(world_path(world), orientation=orientation, joints=joints, seed=seed, config=config)
    from pirate.sim.fake_robot import FakeRobot
    return FakeRobot(pipe_diameter=pipe_diameter, orientation=orientation, joints=joints, seed=seed)
