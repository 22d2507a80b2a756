"""RViz opens framed on the twin's network (pirate.viz.rviz_view), whatever its size."""
import pytest

from pirate.viz import rviz_view
from pirate.world import network


@pytest.mark.parametrize('world,focal,distance', [
    ('straight_90', (0.75, 0.0, 0.0), 3.3),
    ('inspection_network_90', (1.245, 1.29, 0.0), 5.68),
    ('inspection_90', (1.17, 1.59, -1.275), 7.0),
])
def test_the_view_holds_the_whole_network(world, focal, distance):
    found_focal, found_distance = rviz_view.framed_view(network.load(network.world_path(world)))
    assert found_focal == pytest.approx(focal, abs=0.03)
    assert found_distance == pytest.approx(distance, abs=0.05)


def test_the_framed_config_changes_the_view_only():
    with open(rviz_view.TEMPLATE) as stream:
        template = stream.read()
    text = rviz_view.framed_config(template, (1.0, 2.0, -0.5), 4.5)
    assert 'Focal Point: {X: 1.000, Y: 2.000, Z: -0.500}' in text and '      Distance: 4.500' in text
    changed = [(a, b) for a, b in zip(template.splitlines(), text.splitlines()) if a != b]
    assert 'Offset: {X: 1.000, Y: 2.000, Z: -0.5}' in text and '      Pitch: 1.00' in text
    assert len(changed) == 4 and len(text.splitlines()) == len(template.splitlines())


def test_the_estimate_and_the_true_robot_have_different_colours():
    with open(rviz_view.TEMPLATE) as stream:
        template = stream.read()
    assert 'Color: 0; 220; 255' in template        # the estimate; the true robot is the URDF's orange
