"""RViz framed on the twin's network: the view of rviz/world.rviz fitted to a world.

A fixed view framed one world and lost the others (1.5 m to 8 m of pipe).
:func:`framed_view` looks at the middle of the world's pipe path from far
enough to hold all of it; :func:`framed_config` writes it into the
template's view, and :func:`main` (``rosrun pirate twin_rviz WORLD``, as
twin_gui.launch runs it) starts RViz on the result. Pure but for ``main``.
"""
import os
import re
import sys

from pirate import paths
from pirate.world import network, pose

TEMPLATE = os.path.join(os.path.dirname(paths.CONFIG_DIR), 'rviz', 'world.rviz')
#: The view's distance per metre of the world's largest extent, and at least (m): the whole
#: path inside RViz's default field of view (45 degrees) with a margin.
DISTANCE_PER_M, MIN_DISTANCE_M = 2.2, 1.2
#: The view's pitch (rad): steeper than the template's, so the near end of a long network stays in view.
PITCH_RAD = 1.0
PATH_STEP_M = 0.05


def framed_view(world):
    """(focal point xyz m, distance m) that frame the pipe path of ``world`` (a Network)."""
    total = sum(piece.length for piece in world.pieces)
    points = [point for point in pose.path_points(world, 0.0, total, PATH_STEP_M)]
    low = [min(p[i] for p in points) for i in range(3)]
    high = [max(p[i] for p in points) for i in range(3)]
    focal = tuple((a + b) / 2.0 for a, b in zip(low, high))
    extent = max(b - a for a, b in zip(low, high))
    return focal, max(MIN_DISTANCE_M, DISTANCE_PER_M * extent)


def framed_config(template, focal, distance):
    """The RViz config text ``template`` with its view's focal point, distance and pitch
    replaced, and the grid centred under the network."""
    text = re.sub(r'Focal Point: \{[^}]*\}', 'Focal Point: {X: %.3f, Y: %.3f, Z: %.3f}' % focal, template, count=1)
    text = re.sub(r'Offset: \{X: [-0-9.]+, Y: [-0-9.]+,', 'Offset: {X: %.3f, Y: %.3f,' % focal[:2], text, count=1)
    text = re.sub(r'(\n\s+)Pitch: [0-9.]+', r'\g<1>Pitch: %.2f' % PITCH_RAD, text, count=1)
    return re.sub(r'(\n\s+)Distance: [0-9.]+', r'\g<1>Distance: %.3f' % distance, text, count=1)


def main(argv=None):
    """Write the config framed on world ``argv[0]`` next to the ROS logs and start RViz on it
    (with roslaunch's ``__name:=`` and ``__log:=``, so the node keeps its name)."""
    given = sys.argv[1:] if argv is None else argv
    args = [a for a in given if not a.startswith('__')]
    world_name = args[0] if args else 'straight_90'
    focal, distance = framed_view(network.load(network.world_path(world_name)))
    with open(TEMPLATE) as stream:
        text = framed_config(stream.read(), focal, distance)
    folder = os.path.join(os.path.expanduser('~'), '.ros')
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, 'pirate_%s.rviz' % os.path.basename(world_name).replace('.yaml', ''))
    with open(path, 'w') as stream:
        stream.write(text)
    os.execvp('rviz', ['rviz', '-d', path] + [a for a in given if a.startswith('__')])
