"""A pipe network read from YAML, checked, and laid out in 3-D.

Pure (no ROS, no MuJoCo): the physics twin (pirate.sim.twin_model) builds
its walls from :class:`Network`, and the supervisory layer can read the same
file as its pipe map. The format is documented in doc/twin.md ("World
format"); in short::

    name: network_90
    diameter_mm: 90                  # default inner diameter (90 or 110)
    pipe: {outer_mm: 90, sdr: 26}    # optional: the real pipe, its walls inside the size (see below)
    pieces:                          # in travel order, from the robot's start
      - {type: straight, length_mm: 800}
      - {type: mitre, turn: left}    # left | right | up | down
      - {type: straight, length_mm: 400}
      - {type: tee, enter: run, side: right}   # run: straight on, branch open to side
      - {type: straight, length_mm: 400}
      - {type: tee, enter: run, side: left, leave: branch}   # turn left into the branch, run open ahead
      - {type: straight, length_mm: 400}
      - {type: cap}
    obstacles:
      - {type: step, at_mm: 600, height_mm: 4}     # at_mm along the travel path
      - {type: reduction, at_mm: 900, diameter_mm: 80}
      - {type: debris, at_mm: 300, size_mm: 6}
    defects:                         # what an inspection looks for (drawn, not touched)
      - {type: leak, segment: 1, at_mm: 300, clock: 10, size_mm: 12}
    start: {at_mm: 200}              # where the robot's middle starts
    points:                          # named places on the path (the mission's map)
      - {name: launch_pit, at_mm: 200}

A tee is entered through its run or its branch (``enter``) and left by its
run or its branch (``leave``, default ``run``): ``enter: run`` goes straight
on with the branch open to ``side``, or with ``leave: branch`` turns to
``side`` into the branch, the run's far end (ahead) open; ``enter: branch``
turns to ``side`` into the run, its other end open (it cannot leave by the
branch it came in by).

A defect lies in a straight segment: ``segment`` counts the straight
pieces from 0 in travel order, ``at_mm`` is its distance from that
segment's start, ``clock`` its position round the wall (1-12, fractions
allowed) seen looking along the travel direction, 12 at the top, 3 on the
right, and ``size_mm`` its extent (a hole's or patch's diameter, a crack's
or pool's length, a joint's offset, a branch's reach into the pipe).

``pipe`` names the pipe as its standard does (plastic pipes by their outer
diameter): ``outer_mm``, the size whose guards the robot uses (the world's
``diameter_mm``), and its wall, ``wall_mm`` or its standard dimension ratio
``sdr`` (about outer / wall; the wall the standards list,
:data:`STANDARD_WALLS_MM`). The bore is ``outer_mm`` - 2 wall; the pieces keep the size as
their layout (a fitting's centre lines) and the twin stands its walls at
the bore. Without ``pipe`` the bore is the diameter.

Each piece has an entry frame; its exit frame is where the next piece
starts. Frames are (origin, 3x3 rotation as rows of the x/y/z axes) in
metres: x along the travel direction, y to the left, z up.
"""
import collections
import math
import os

import yaml

from pirate import paths

DIAMETERS_MM = (90, 110)
#: Nominal walls (mm) of plastic pipes by outer diameter and standard
#: dimension ratio: ISO 4065's series as EN 12201-2 / EN 1555-2 (PE) and
#: EN 1452-2 (PVC-U: SDR 41, 33, 26, 21, 17 are S 20, 16, 12.5, 10, 8) list them.
STANDARD_WALLS_MM = {
    90: {41: 2.2, 33: 2.8, 26: 3.5, 21: 4.3, 17: 5.4, 13.6: 6.7, 11: 8.2},
    110: {41: 2.7, 33: 3.4, 26: 4.2, 21: 5.3, 17: 6.6, 13.6: 8.1, 11: 10.0},
}
WORLDS_DIR = os.path.join(paths.CONFIG_DIR, 'worlds')
TURNS = {'left': ((0, 0, 1), 1), 'right': ((0, 0, 1), -1), 'up': ((0, 1, 0), -1), 'down': ((0, 1, 0), 1)}
PIECE_KEYS = {
    'straight': {'length_mm': True, 'diameter_mm': False},
    'mitre': {'turn': True},
    'tee': {'enter': True, 'side': True, 'leave': False},
    'cap': {},
}
OBSTACLE_KEYS = {
    'step': {'at_mm': True, 'height_mm': True},
    'reduction': {'at_mm': True, 'diameter_mm': True, 'length_mm': False},
    'debris': {'at_mm': True, 'size_mm': True},
}
DEFECT_KEYS = {kind: {'segment': True, 'at_mm': True, 'clock': True, 'size_mm': True}
               for kind in ('leak', 'crack', 'corrosion', 'deposit', 'water', 'displaced_joint', 'intruding_branch')}
#: Defects whose size is how far they reach into the pipe (below its radius).
INTO_PIPE = ('displaced_joint', 'intruding_branch')
TEE_ENTRIES = ('run', 'branch')
#: How a tee may be left, by how it is entered (the branch it came in by is not a way out).
TEE_EXITS = {'run': ('run', 'branch'), 'branch': ('run',)}
OVERLAP_SAMPLE_M = 0.01

#: One laid-out piece: kind, its entry-data, diameter (m), entry frame,
#: exit frame, path length along its axis (m), and the open stub's frame
#: (tee only, None otherwise).
Piece = collections.namedtuple('Piece', 'kind spec diameter entry exit length stub')
Frame = collections.namedtuple('Frame', 'origin axes')
#: One defect: kind, straight segment index, piece index, metres from the
#: segment's start, metres along the whole path, clock (1-12), size (m).
Defect = collections.namedtuple('Defect', 'kind segment piece at along clock size')


class WorldError(ValueError):
    """A world file that cannot be built: says the file, the entry and why."""


def _vec_add(a, b, scale=1.0):
    return tuple(x + scale * y for x, y in zip(a, b))


def _rotate(axes, axis_index, sign):
    """Turn a frame 90 deg about its own axis ``axis_index`` (1 = y, 2 = z)."""
    x, y, z = axes
    neg = tuple(-c for c in x)
    if axis_index == 2:      # yaw: left (+) swaps x -> y
        return (y, neg, z) if sign > 0 else (tuple(-c for c in y), x, z)
    # pitch about y: down (+) turns x to -z
    return ((tuple(-c for c in z), y, x) if sign > 0 else (z, y, neg))


def turned(frame, turn):
    """The frame after a 90 deg ``turn`` (left/right/up/down) at its origin."""
    axis, sign = TURNS[turn]
    return Frame(frame.origin, _rotate(frame.axes, axis.index(1), sign))


#: Path step (m) of :meth:`Network.nearest_along`'s coarse search; its fine
#: one is FINE_STEPS steps of a fiftieth either side (0.1 mm).
PROJECT_STEP_M = 0.005
FINE_STEPS = 50
#: How far (m) from where a moving robot was :meth:`Network.nearest_along`
#: looks: far above what it travels between two samples of a run.
NEAR_WINDOW_M = 0.2


class Network(object):
    """Pieces and obstacles in travel order, laid out from the origin."""

    def __init__(self, name, pieces, obstacles, start_m, source='<world>', points=None, defects=(), bore_offset_m=0.0):
        self.name, self.pieces, self.obstacles = name, pieces, obstacles
        self.bore_offset_m = bore_offset_m      # the bore minus the size, m (``pipe``; 0 without)
        self.defects = list(defects)
        self.start_m, self.source = start_m, source
        self.points = dict(points or {})    # name -> metres along the path

    @property
    def length(self):
        """Path length from the first piece's entry to the last exit, m."""
        return sum(p.length for p in self.pieces)

    def locate(self, along_m):
        """(piece index, Frame at ``along_m`` on the path axis): straight
        pieces only report their own axis; for bends the entry axes are used."""
        travelled = 0.0
        for index, piece in enumerate(self.pieces):
            if along_m <= travelled + piece.length or index == len(self.pieces) - 1:
                offset = along_m - travelled
                axes = piece.entry.axes
                if piece.kind == 'mitre' and offset > piece.length / 2:
                    axes = piece.exit.axes
                    return index, Frame(_vec_add(piece.exit.origin, axes[0], offset - piece.length), axes)
                return index, Frame(_vec_add(piece.entry.origin, axes[0], offset), axes)
            travelled += piece.length
        raise WorldError('%s: empty network' % self.source)

    def diameter_at(self, along_m):
        """Inner diameter (m) of the piece at ``along_m``."""
        return self.pieces[self.locate(along_m)[0]].diameter

    def nearest_along(self, position, near_m=None):
        """The path position (m) nearest to ``position`` (world, m): every
        :data:`PROJECT_STEP_M` of the path (or within :data:`NEAR_WINDOW_M`
        of ``near_m``, where it was a moment ago, unless the best is at that
        window's edge), then to a fiftieth of that around the best."""
        def dist(along):
            return sum((a - b) ** 2 for a, b in zip(self.locate(along)[1].origin, position))
        low, high = 0.0, self.length
        if near_m is not None:
            low, high = max(low, near_m - NEAR_WINDOW_M), min(high, near_m + NEAR_WINDOW_M)
        steps = int((high - low) / PROJECT_STEP_M)
        coarse = min((low + i * PROJECT_STEP_M for i in range(steps + 1)), key=dist)
        if near_m is not None and (0.0 < low == coarse or coarse == low + steps * PROJECT_STEP_M < self.length):
            return self.nearest_along(position)     # it moved farther than the window: look everywhere
        fine = [coarse + (i - FINE_STEPS) * PROJECT_STEP_M / FINE_STEPS for i in range(2 * FINE_STEPS + 1)]
        return min((a for a in fine if low <= a <= high), key=dist)


def world_path(world):
    """A world file: a path, or a name under config/worlds/ ('straight_90')."""
    if os.path.sep in world or world.endswith('.yaml'):
        return world
    return os.path.join(WORLDS_DIR, world + '.yaml')


def load(path):
    """Read and check the world file at ``path``; return a :class:`Network`."""
    try:
        with open(path) as stream:
            data = yaml.safe_load(stream)
    except (OSError, yaml.YAMLError) as error:
        raise WorldError('%s: cannot read: %s' % (path, error))
    return build(data, source=path)


def build(data, source='<world>'):
    """Check ``data`` (the parsed YAML) and lay the network out."""
    if not isinstance(data, dict):
        raise WorldError('%s: a world is a mapping with pieces, got %r' % (source, type(data).__name__))
    unknown = set(data) - {'name', 'diameter_mm', 'pipe', 'pieces', 'obstacles', 'defects', 'start', 'points'}
    if unknown:
        raise WorldError('%s: unknown top-level key(s) %s' % (source, sorted(unknown)))
    default_mm = _diameter(data.get('diameter_mm', 90), source, 'diameter_mm')
    specs = data.get('pieces') or []
    if not isinstance(specs, list) or not specs:
        raise WorldError('%s: pieces: a non-empty list is needed' % source)
    pieces = _lay_out(specs, default_mm, source)
    _check_overlap(pieces, source)
    total = sum(p.length for p in pieces)
    obstacles = [_obstacle(i, spec, total, source) for i, spec in enumerate(data.get('obstacles') or [])]
    start = data.get('start') or {}
    start_m = float(start.get('at_mm', 200)) / 1000.0
    if not 0.0 < start_m < total or pieces[_piece_at(pieces, start_m)].kind != 'straight':
        raise WorldError('%s: start: at_mm %.0f is not inside a straight piece' % (source, start_m * 1000))
    points = _points(data.get('points') or [], total, source)
    defects = _defects(data.get('defects') or [], pieces, source)
    bore_offset_m = _bore_offset(data.get('pipe'), default_mm, pieces, source)
    return Network(data.get('name', source), pieces, obstacles, start_m, source, points, defects, bore_offset_m)


def pipe_wall_mm(outer_mm, sdr):
    """The nominal wall (mm) of a plastic pipe of ``outer_mm`` and standard
    dimension ratio ``sdr`` (:data:`STANDARD_WALLS_MM`); raises ValueError
    for a ratio the standards do not list at that size."""
    walls = STANDARD_WALLS_MM.get(outer_mm, {})
    if sdr not in walls:
        raise ValueError('sdr %r is not a standard series of a %s mm pipe (one of %s; or give wall_mm)'
                         % (sdr, outer_mm, ', '.join('%g' % k for k in sorted(walls))))
    return walls[sdr]


def _bore_offset(spec, size_mm, pieces, source):
    """The bore minus the size (m) of a world's ``pipe``, checked; 0 without one."""
    if spec is None:
        return 0.0
    if not isinstance(spec, dict) or set(spec) - {'outer_mm', 'wall_mm', 'sdr'} or 'outer_mm' not in spec \
            or len(set(spec) & {'wall_mm', 'sdr'}) != 1:
        raise WorldError('%s: pipe: {outer_mm, and wall_mm or sdr} is needed, got %r' % (source, spec))
    if spec['outer_mm'] != size_mm or any(abs(p.diameter * 1000 - size_mm) > 1e-6 for p in pieces):
        raise WorldError('%s: pipe: outer_mm %r must be the size of every piece, diameter_mm %d'
                         % (source, spec['outer_mm'], size_mm))
    if 'sdr' in spec:
        try:
            wall_mm = pipe_wall_mm(size_mm, spec['sdr'])
        except ValueError as bad:
            raise WorldError('%s: pipe: %s' % (source, bad))
    elif isinstance(spec['wall_mm'], (int, float)) and not isinstance(spec['wall_mm'], bool):
        wall_mm = float(spec['wall_mm'])
    else:
        raise WorldError('%s: pipe: wall_mm %r is not a number' % (source, spec['wall_mm']))
    if not 0.0 < wall_mm < size_mm / 8.0:
        raise WorldError('%s: pipe: a wall of %.1f mm in a %d mm pipe is not a pipe the robot fits in'
                         % (source, wall_mm, size_mm))
    return -2.0 * wall_mm / 1000.0


def _defects(specs, pieces, source):
    """The defects as :data:`Defect`, each checked against its segment."""
    if not isinstance(specs, list):
        raise WorldError('%s: defects: a list of {type, segment, at_mm, clock, size_mm} is needed' % source)
    straights = [i for i, p in enumerate(pieces) if p.kind == 'straight']
    return [_defect(i, spec, pieces, straights, source) for i, spec in enumerate(specs)]


def _number(spec, key, source, where):
    value = spec[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise WorldError('%s: %s: %s %r is not a number' % (source, where, key, value))
    return float(value)


def _defect(index, spec, pieces, straights, source):
    where = 'defects[%d]' % index
    kind = _check_keys(spec, DEFECT_KEYS, source, where)
    where = '%s (%s)' % (where, kind)
    segment = spec['segment']
    if isinstance(segment, bool) or not isinstance(segment, int) or not 0 <= segment < len(straights):
        raise WorldError('%s: %s: segment %r is not a straight segment (0..%d, counted in travel order)'
                         % (source, where, segment, len(straights) - 1))
    piece_index = straights[segment]
    piece = pieces[piece_index]
    at_m = _number(spec, 'at_mm', source, where) / 1000.0
    if not 0.0 <= at_m <= piece.length:
        raise WorldError('%s: %s: at_mm %.0f is beyond segment %d (0..%.0f mm)'
                         % (source, where, at_m * 1000, segment, piece.length * 1000))
    clock = _number(spec, 'clock', source, where)
    if not 1.0 <= clock <= 12.0:
        raise WorldError('%s: %s: clock %g is not a clock position (1-12, 12 at the top, 3 on the right)'
                         % (source, where, clock))
    size_m = _number(spec, 'size_mm', source, where) / 1000.0
    largest = piece.diameter / 2 if kind in INTO_PIPE else piece.length
    if not 0.0 < size_m < largest:
        raise WorldError('%s: %s: size_mm %.0f must be > 0 and below %.0f mm (%s)'
                         % (source, where, size_m * 1000, largest * 1000,
                            'the pipe radius' if kind in INTO_PIPE else 'the segment length'))
    along = sum(p.length for p in pieces[:piece_index]) + at_m
    return Defect(kind, segment, piece_index, at_m, along, clock, size_m)


def clock_direction(axes, clock):
    """Unit vector from the pipe's axis to ``clock`` (1-12) round the wall of
    a pipe whose frame rows are ``axes``: 12 is up (z), 3 right (-y), looking
    along x."""
    angle = math.radians(30.0 * clock)
    return tuple(math.cos(angle) * z - math.sin(angle) * y for y, z in zip(axes[1], axes[2]))


def _points(specs, total_m, source):
    """Named places on the path: {name: metres along}; names unique, inside."""
    if not isinstance(specs, list):
        raise WorldError('%s: points: a list of {name, at_mm} is needed' % source)
    points = {}
    for index, spec in enumerate(specs):
        where = 'points[%d]' % index
        if not isinstance(spec, dict) or set(spec) != {'name', 'at_mm'}:
            raise WorldError('%s: %s: a point is {name: ..., at_mm: ...}, got %r' % (source, where, spec))
        name = str(spec['name'])
        if name in points:
            raise WorldError('%s: %s: point %r is named twice' % (source, where, name))
        at_m = float(spec['at_mm']) / 1000.0
        if not 0.0 <= at_m <= total_m:
            raise WorldError('%s: %s (%s): at_mm %.0f is outside the network (0..%.0f mm)'
                             % (source, where, name, at_m * 1000, total_m * 1000))
        points[name] = at_m
    return points


def _piece_at(pieces, along_m):
    travelled = 0.0
    for index, piece in enumerate(pieces):
        travelled += piece.length
        if along_m <= travelled:
            return index
    return len(pieces) - 1


def _diameter(value, source, where):
    if value not in DIAMETERS_MM:
        raise WorldError('%s: %s: diameter %r mm is not supported (only %s)'
                         % (source, where, value, ', '.join(map(str, DIAMETERS_MM))))
    return value


def _check_keys(spec, table, source, where):
    if not isinstance(spec, dict) or 'type' not in spec:
        raise WorldError('%s: %s: an entry is a mapping with a type, got %r' % (source, where, spec))
    kind = spec['type']
    if kind not in table:
        raise WorldError('%s: %s: unknown element %r (known: %s)' % (source, where, kind, ', '.join(table)))
    keys = table[kind]
    missing = [k for k, needed in keys.items() if needed and k not in spec]
    extra = set(spec) - set(keys) - {'type'}
    if missing or extra:
        raise WorldError('%s: %s (%s): missing %s, unknown %s'
                         % (source, where, kind, missing or '-', sorted(extra) or '-'))
    return kind


def _lay_out(specs, default_mm, source):
    frame = Frame((0.0, 0.0, 0.0), ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))
    pieces, diameter_mm = [], default_mm
    for index, spec in enumerate(specs):
        where = 'pieces[%d]' % index
        kind = _check_keys(spec, PIECE_KEYS, source, where)
        follows = specs[index + 1]['type'] if index + 1 < len(specs) and isinstance(specs[index + 1], dict) else None
        if kind in ('mitre', 'tee') and follows != 'straight':
            raise WorldError('%s: %s (%s): a bend or T-joint needs a straight segment after it, got %s'
                             % (source, where, kind, follows or 'the end of the list'))
        if kind == 'cap' and index != len(specs) - 1:
            raise WorldError('%s: %s (cap): an end cap must be the last piece' % (source, where))
        if kind == 'straight':
            diameter_mm = _diameter(spec.get('diameter_mm', default_mm), source, where)
            if not float(spec['length_mm']) > 0:
                raise WorldError('%s: %s (straight): length_mm must be > 0' % (source, where))
        piece = _piece(kind, spec, diameter_mm / 1000.0, frame, source, where)
        pieces.append(piece)
        frame = piece.exit
    return pieces


def _piece(kind, spec, diameter, entry, source, where):
    if kind == 'straight':
        length = float(spec['length_mm']) / 1000.0
        return Piece(kind, spec, diameter, entry, Frame(_vec_add(entry.origin, entry.axes[0], length), entry.axes),
                     length, None)
    if kind == 'cap':
        return Piece(kind, spec, diameter, entry, entry, 0.0, None)
    turn = spec.get('turn') if kind == 'mitre' else spec.get('side')
    if turn not in TURNS:
        raise WorldError('%s: %s (%s): direction %r is not one of %s' % (source, where, kind, turn, ', '.join(TURNS)))
    corner = Frame(_vec_add(entry.origin, entry.axes[0], diameter / 2), entry.axes)
    side = turned(corner, turn)
    out = Frame(_vec_add(side.origin, side.axes[0], diameter / 2), side.axes)     # where a turn leaves
    if kind == 'mitre':
        return Piece(kind, spec, diameter, entry, out, diameter, None)
    _check_tee(spec, source, where)
    if spec['enter'] == 'branch':       # turn to the side into the run; its other end is open
        opposite = turned(turned(side, turn), turn)
        return Piece(kind, spec, diameter, entry, out, diameter, Frame(opposite.origin, opposite.axes))
    if tee_leaves_by(spec) == 'branch':     # turn to the side into the branch; the run ahead is open
        return Piece(kind, spec, diameter, entry, out, diameter, Frame(corner.origin, corner.axes))
    ahead = Frame(_vec_add(corner.origin, corner.axes[0], diameter / 2), corner.axes)   # straight on
    return Piece(kind, spec, diameter, entry, ahead, diameter, Frame(side.origin, side.axes))


def _check_tee(spec, source, where):
    """Refuse an unknown ``enter`` / ``leave``, and leaving by the branch entered by."""
    if spec['enter'] not in TEE_ENTRIES:
        raise WorldError('%s: %s (tee): enter %r is not one of %s' % (source, where, spec['enter'], TEE_ENTRIES))
    leave = tee_leaves_by(spec)
    if leave not in TEE_EXITS['run']:
        raise WorldError('%s: %s (tee): leave %r is not one of %s' % (source, where, leave, TEE_EXITS['run']))
    if leave not in TEE_EXITS[spec['enter']]:
        raise WorldError('%s: %s (tee): entered through its branch, it can only be left by its run (leave: run), '
                         'not by the branch it came in by' % (source, where))


def tee_leaves_by(spec):
    """'run' or 'branch': how the path leaves a tee (its ``leave``, default run)."""
    return spec.get('leave', 'run')


def turns_at_corner(piece):
    """True when the path turns at ``piece``'s corner (a mitre bend, a tee
    entered through its branch or left by it), False straight on (a tee
    through its run) or for a piece with no corner."""
    if piece.kind == 'mitre':
        return True
    return piece.kind == 'tee' and (piece.spec['enter'] == 'branch' or tee_leaves_by(piece.spec) == 'branch')


def _axis_samples(piece):
    """Points on the centre line of ``piece`` (and of a tee's stub)."""
    points = []
    segments = [(piece.entry.origin, piece.exit.origin)]
    if turns_at_corner(piece):
        corner = _vec_add(piece.entry.origin, piece.entry.axes[0], piece.diameter / 2)
        segments = [(piece.entry.origin, corner), (corner, piece.exit.origin)]
    if piece.stub is not None:
        segments.append((piece.stub.origin, _vec_add(piece.stub.origin, piece.stub.axes[0], piece.diameter / 2)))
    for a, b in segments:
        n = max(1, int(math.dist(a, b) / OVERLAP_SAMPLE_M))
        points += [tuple(a[k] + (b[k] - a[k]) * i / n for k in range(3)) for i in range(n + 1)]
    return points


def _check_overlap(pieces, source):
    """Refuse two pieces, more than two apart, whose centre lines come closer
    than one diameter (their walls would cut into each other)."""
    samples = [_axis_samples(p) for p in pieces]
    for i in range(len(pieces)):
        for j in range(i + 3, len(pieces)):     # i + 1, i + 2 share a joint or a corner
            gap = max(pieces[i].diameter, pieces[j].diameter)
            if any(math.dist(a, b) < gap for a in samples[i] for b in samples[j]):
                raise WorldError('%s: pieces[%d] (%s) overlaps pieces[%d] (%s)'
                                 % (source, j, pieces[j].kind, i, pieces[i].kind))


def _obstacle(index, spec, total_m, source):
    where = 'obstacles[%d]' % index
    kind = _check_keys(spec, OBSTACLE_KEYS, source, where)
    at_m = float(spec['at_mm']) / 1000.0
    if not 0.0 <= at_m <= total_m:
        raise WorldError('%s: %s (%s): at_mm %.0f is outside the network (0..%.0f mm)'
                         % (source, where, kind, at_m * 1000, total_m * 1000))
    if kind == 'reduction' and not 0 < spec['diameter_mm'] < 110:
        raise WorldError('%s: %s (reduction): diameter_mm %r is not a reduction' % (source, where, spec['diameter_mm']))
    return dict(spec, at_m=at_m)
