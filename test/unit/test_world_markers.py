"""What RViz draws of the twin's world (pirate.viz.world_markers, pure)."""
import math
import os

import pytest

from pirate import paths
from pirate.viz import world_markers
from pirate.world import network

GEOMETRY = {'module_length_m': 0.09, 'body_radius_m': 0.02,
            'wheel_diameter_m': 0.046, 'wheel_half_width_m': 0.006}


def _rotate_z(quat_xyzw):
    x, y, z, w = quat_xyzw
    return (2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y))


@pytest.mark.parametrize('axis', [(1, 0, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1), (0.6, 0.8, 0)])
def test_z_to_turns_z_onto_the_axis(axis):
    assert _rotate_z(world_markers.z_to(axis)) == pytest.approx(axis, abs=1e-9)


def test_every_piece_of_the_network_is_drawn():
    world = network.load(os.path.join(paths.CONFIG_DIR, 'worlds', 'network_90.yaml'))
    shapes = world_markers.pipe_shapes(world)
    # 4 straights, 2 mitres x 2 legs, tee run x 2 + branch, 1 cap
    assert len(shapes) == 4 + 4 + 3 + 1
    first = shapes[0]
    assert first[1] == pytest.approx((0.45, 0.0, 0.0)) and first[3] == pytest.approx((0.09, 0.09, 0.9))


def test_a_tee_left_by_its_branch_is_drawn_turning_with_its_run_going_on_ahead():
    world = network.build({'pieces': [{'type': 'straight', 'length_mm': 500},
                                      {'type': 'tee', 'enter': 'run', 'side': 'left', 'leave': 'branch'},
                                      {'type': 'straight', 'length_mm': 300}]})
    _, leg_in, leg_out, stub, _ = world_markers.pipe_shapes(world)
    corner = (0.545, 0.0, 0.0)
    assert leg_in[1] == pytest.approx((0.5225, 0.0, 0.0))
    assert leg_out[1] == pytest.approx((0.545, 0.0225, 0.0))        # half a diameter toward the branch
    assert stub[1] == pytest.approx((corner[0] + 0.045, 0.0, 0.0))  # one diameter of run on ahead


def test_robot_shells_reach_from_their_joint_and_wheels_sit_on_it():
    upright = (1.0, 0.0, 0.0, 0.0)
    pitched = (math.cos(0.25), 0.0, math.sin(0.25), 0.0)       # 0.5 rad about y
    shapes = world_markers.robot_shapes([((0, 0, 0), upright), ((1, 0, 0), pitched)], (1, -2), GEOMETRY)
    kinds = [s[0] for s in shapes]
    assert kinds == ['shell', 'wheel', 'shell']                     # a half module has no wheel
    assert shapes[0][1] == pytest.approx((0.045, 0, 0)) and shapes[1][1] == (0, 0, 0)
    assert shapes[0][3] == pytest.approx((0.04, 0.04, 0.09))        # round, as long as the module
    assert world_markers._rotate((shapes[0][2][3],) + tuple(shapes[0][2][:3]), (0, 0, 1)) == pytest.approx((1, 0, 0))
    centre = shapes[2][1]                                       # 22.5 mm back along the pitched x
    assert centre == pytest.approx((1 - 0.0225 * math.cos(0.5), 0, 0.0225 * math.sin(0.5)))


def test_each_defect_is_a_marker_on_the_wall_at_its_clock():
    world = network.build({'pieces': [{'type': 'straight', 'length_mm': 1000}, {'type': 'cap'}],
                           'defects': [{'type': 'leak', 'segment': 0, 'at_mm': 600, 'clock': 3, 'size_mm': 2},
                                       {'type': 'deposit', 'segment': 0, 'at_mm': 300, 'clock': 12, 'size_mm': 30}]})
    (kind, leak, _, leak_size), (_, deposit, _, deposit_size) = world_markers.defect_shapes(world)
    assert kind == 'defect'
    assert leak == pytest.approx((0.6, -0.045, 0.0)) and deposit == pytest.approx((0.3, 0.0, 0.045))
    assert leak_size == (world_markers.DEFECT_MIN_M,) * 3 and deposit_size == pytest.approx((0.03,) * 3)
