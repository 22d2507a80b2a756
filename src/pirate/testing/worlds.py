"""World files made from the ones in config/worlds/ by a small change, for
a twin whose pipe is not what its map says (the map stays the original)."""
import os
import tempfile

import yaml

from pirate.world import network

JUNCTIONS = ('mitre', 'tee')


def junction_moved(world, moved_mm, directory=None):
    """The path of a world file like ``world`` (a name or path) whose first
    junction lies ``moved_mm`` further on along the path: the straight
    before it that much longer (shorter for a negative ``moved_mm``).
    Written in ``directory`` (default: a new temporary one)."""
    with open(network.world_path(world)) as stream:
        layout = yaml.safe_load(stream)
    pieces = [dict(piece) for piece in layout['pieces']]
    first = next(i for i, piece in enumerate(pieces) if piece['type'] in JUNCTIONS)
    if first == 0 or pieces[first - 1]['type'] != 'straight':
        raise ValueError('%s: no straight before its first junction to lengthen' % world)
    pieces[first - 1]['length_mm'] += moved_mm
    name = '%s_junction_moved_%.0f_mm' % (layout['name'], moved_mm)
    path = os.path.join(directory or tempfile.mkdtemp(prefix='pirate_world_'), name + '.yaml')
    with open(path, 'w') as sink:
        yaml.safe_dump(dict(layout, name=name, pieces=pieces), sink)
    network.load(path)        # checked as the twin will read it
    return path
