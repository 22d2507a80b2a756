"""The pipe walls of the physics twin (pirate.sim.twin_pipes): boxes that leave the pipe's bore free.

A wall box standing inside the bore is a step no real pipe has: at a
T-joint's rim one square to the path stalled a wheel. Pure geometry of the
generated MJCF, no MuJoCo.
"""
import itertools
import math
import xml.etree.ElementTree as ET

import pytest

from pirate.sim.twin_pipes import WallBuilder
from pirate.world import network

#: A corner this far inside the bore counts (m): MuJoCo's contact margin is larger than float noise.
INSIDE_M = 0.0005


def box_corners(geom):
    """The 8 corners (world, m) of a box geom."""
    centre = [float(v) for v in geom.get('pos').split()]
    axes = [float(v) for v in geom.get('xyaxes').split()]
    x_axis, y_axis = axes[:3], axes[3:]
    z_axis = (x_axis[1] * y_axis[2] - x_axis[2] * y_axis[1], x_axis[2] * y_axis[0] - x_axis[0] * y_axis[2],
              x_axis[0] * y_axis[1] - x_axis[1] * y_axis[0])
    half = [float(v) for v in geom.get('size').split()]
    for signs in itertools.product((-1, 1), repeat=3):
        yield tuple(centre[k] + sum(s * h * axis[k] for s, h, axis in zip(signs, half, (x_axis, y_axis, z_axis)))
                    for k in range(3))


@pytest.mark.parametrize('world_name', ['tee_run_left_90', 'tee_run_right_110', 'tee_run_up_90', 'tee_run_down_90'])
def test_no_wall_box_of_a_t_joint_stands_inside_its_run(world_name):
    """The worlds run along x from the origin: every wall corner over the
    T-joint's run lies at least the radius off the x axis."""
    world = network.load(network.world_path(world_name))
    tee = world.pieces[1]
    radius = tee.diameter / 2
    body = ET.Element('worldbody')
    WallBuilder(body).network(world)
    start_x, end_x = tee.entry.origin[0], tee.entry.origin[0] + tee.diameter
    inside = []
    for geom in body.iter('geom'):
        if not geom.get('name', '').startswith('wall'):
            continue
        for x, y, z in box_corners(geom):
            if start_x < x < end_x and math.hypot(y, z) < radius - INSIDE_M:
                inside.append((geom.get('name'), round(x, 4), round(math.hypot(y, z), 4)))
    assert not inside, inside[:5]
