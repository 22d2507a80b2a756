"""The pipe network as MuJoCo geoms: hollow walls from convex boxes.

A pipe is ``wall_segments`` boxes around its circumference, their inner
faces at the pipe radius. A mitre bend is two such legs cut on the bend's
45 deg plane (each box as long as the cut allows at its angle), so the
corner is really there; a T-joint's run has the branch's hole cut out and
the open side is left open (entered through the run or the branch, left by
either); an end cap is a plate. Obstacles: a step is a
plate on the floor, a reduction a narrower ring, debris a loose box.
Defects (a leak, crack, corrosion, deposit, water, a displaced joint, an
intruding branch) are visual geoms on the wall's inside, in their own
group: the cameras see them, no contact touches them.
Pure (no MuJoCo import): it writes MJCF elements.
"""
import math
import xml.etree.ElementTree as ET

from pirate.world.network import clock_direction, tee_leaves_by

PIPE_CLASS = 'pipe'
PIPE_GROUP = 1          # MuJoCo geom group of walls and obstacles (rays, rendering)
DEFECT_GROUP = 2        # MuJoCo geom group of defects: drawn, never in contact
MIN_BOX_M = 0.001
#: How each defect looks (rgba): a hole dark, corrosion rust, a deposit
#: grey-brown, water blue, a joint's ring and a branch pipe grey.
DEFECT_RGBA = {'leak': '0.02 0.02 0.02 1', 'crack': '0.05 0.03 0.02 1', 'corrosion': '0.6 0.25 0.05 1',
               'deposit': '0.45 0.4 0.3 1', 'water': '0.2 0.45 0.9 0.8', 'displaced_joint': '0.5 0.5 0.5 1',
               'intruding_branch': '0.85 0.85 0.8 1'}
DEFECT_FILM_M = 0.0005      # a flat defect's thickness, just inside the wall
BRANCH_RADIUS_M = 0.008     # an intruding branch's pipe
JOINT_WIDTH_M = 0.01        # a displaced joint's visible ring along the pipe


def _add(a, b, scale=1.0):
    return tuple(x + scale * y for x, y in zip(a, b))


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _fmt(values):
    return ' '.join('%.6g' % v for v in values)


class WallBuilder(object):
    """Adds the geoms of a :class:`pirate.world.network.Network` to ``parent``."""

    def __init__(self, parent, segments=24, thickness=0.004, bore_error=0.0):
        self.parent, self.segments, self.thickness = parent, segments, thickness
        self.radius_error = bore_error / 2      # m: the real bore minus the world's diameter, halved (wall_radius)
        self.count = 0

    def box(self, centre, x_axis, y_axis, half, name_hint='wall', rgba=None):
        """One static box; ``x_axis``/``y_axis`` give its orientation."""
        attrs = dict(type='box', pos=_fmt(centre), xyaxes=_fmt(x_axis + y_axis), size=_fmt(half),
                     name='%s%d' % (name_hint, self.count), **{'class': PIPE_CLASS})
        if rgba:
            attrs['rgba'] = rgba
        ET.SubElement(self.parent, 'geom', attrs)
        self.count += 1

    def _ring(self, axes):
        """(radial, tangential) unit vectors of each wall segment of a pipe
        whose frame rows are ``axes`` (x along the pipe)."""
        _, y, z = axes
        for k in range(self.segments):
            phi = 2 * math.pi * (k + 0.5) / self.segments
            radial = _add(tuple(c * math.cos(phi) for c in y), z, math.sin(phi))
            tangent = _add(tuple(-c * math.sin(phi) for c in y), z, math.cos(phi))
            yield radial, tangent

    def tube(self, origin, axes, radius, spans, box=None):
        """Wall of a pipe along axes[0] from ``origin``; ``spans(radial)``
        returns the (start, end) intervals (m along the axis) of the wall
        at that radial direction; ``box`` adds each box (default :meth:`box`)."""
        half_width = radius * math.tan(math.pi / self.segments) + self.thickness / 2
        for radial, tangent in self._ring(axes):
            for start, end in spans(radial):
                if end - start < MIN_BOX_M:
                    continue
                centre = _add(_add(origin, axes[0], (start + end) / 2), radial, radius + self.thickness / 2)
                (box or self.box)(centre, axes[0], radial, ((end - start) / 2, self.thickness / 2, half_width))

    def plate(self, centre, axes, radius):
        """A disc closing a pipe end (an end cap), as one square plate."""
        self.box(_add(centre, axes[0], self.thickness / 2), axes[1], axes[2],
                 (radius + self.thickness, radius + self.thickness, self.thickness / 2))

    def network(self, world):
        """Every piece and obstacle of ``world``."""
        for piece in world.pieces:
            getattr(self, '_' + piece.kind)(piece)
        for obstacle in world.obstacles:
            getattr(self, '_obstacle_' + obstacle['type'])(world, obstacle)
        for defect in world.defects:
            self.defect(world.pieces[defect.piece], defect)

    def _visual(self, attrs, kind):
        attrs.update(contype='0', conaffinity='0', group=str(DEFECT_GROUP), rgba=DEFECT_RGBA[kind],
                     name='defect_%s%d' % (kind, self.count))
        ET.SubElement(self.parent, 'geom', attrs)
        self.count += 1

    def defect(self, piece, defect):
        """A defect's visual geoms on ``piece``'s wall (a straight segment)."""
        axes, radius = piece.entry.axes, self.wall_radius(piece)
        radial = clock_direction(axes, defect.clock)
        centre = _add(piece.entry.origin, axes[0], defect.at)
        tangent = tuple(a * b - c * d for a, b, c, d in (
            (radial[1], axes[0][2], radial[2], axes[0][1]), (radial[2], axes[0][0], radial[0], axes[0][2]),
            (radial[0], axes[0][1], radial[1], axes[0][0])))
        size, kind = defect.size, defect.kind
        if kind == 'displaced_joint':       # the next pipe's rim shifted away from the clock: a lip of ``size`` there
            self.tube(_add(centre, radial, -size), axes, radius, lambda r: [(0.0, JOINT_WIDTH_M)],
                      lambda c, x, y, half: self._visual(
                          dict(type='box', pos=_fmt(c), xyaxes=_fmt(x + y), size=_fmt(half)), kind))
            return
        if kind == 'intruding_branch':      # a small pipe from the wall into the bore
            self._visual(dict(type='cylinder', pos=_fmt(_add(centre, radial, radius - size / 2)),
                              zaxis=_fmt(radial), size=_fmt((BRANCH_RADIUS_M, size / 2))), kind)
            return
        if kind == 'deposit':               # a mound on the wall
            self._visual(dict(type='ellipsoid', pos=_fmt(_add(centre, radial, radius)), zaxis=_fmt(radial),
                              size=_fmt((size / 2, size / 2, size / 4))), kind)
            return
        inside = _add(centre, radial, radius - DEFECT_FILM_M)
        if kind in ('crack', 'water'):      # long along the pipe: a crack narrow, a pool wide
            width = 0.0015 if kind == 'crack' else radius * 0.6
            self._visual(dict(type='box', pos=_fmt(inside), xyaxes=_fmt(axes[0] + tangent),
                              size=_fmt((size / 2, width / 2, DEFECT_FILM_M))), kind)
            return
        self._visual(dict(type='cylinder', pos=_fmt(inside), zaxis=_fmt(radial),     # a hole, a patch
                          size=_fmt((size / 2, DEFECT_FILM_M))), kind)

    def wall_radius(self, piece):
        """Where ``piece``'s wall stands (m from its axis): half its size as
        laid out, plus half the bore's error (a real pipe's wall, a tolerance)."""
        return piece.diameter / 2 + self.radius_error

    def _straight(self, piece):
        self.tube(piece.entry.origin, piece.entry.axes, self.wall_radius(piece),
                  lambda radial: [(0.0, piece.length)])

    def _cap(self, piece):
        self.plate(piece.entry.origin, piece.entry.axes, self.wall_radius(piece))

    def _mitre(self, piece):
        radius, wall = piece.diameter / 2, self.wall_radius(piece)
        x_in, x_out = piece.entry.axes[0], piece.exit.axes[0]
        # Leg in: cut where (s - R) + r (radial . x_out) = 0 (R the corner's offset, r the wall's); leg out likewise.
        self.tube(piece.entry.origin, piece.entry.axes, wall,
                  lambda r: [(0.0, radius - wall * _dot(r, x_out))])
        back = tuple(tuple(-c for c in axis) for axis in piece.exit.axes[:2]) + (piece.exit.axes[2],)
        self.tube(piece.exit.origin, back, wall,
                  lambda r: [(0.0, radius + wall * _dot(r, x_in))])

    def _tee(self, piece):
        """Run with a hole where the branch meets it; branch cut to the run.
        The pipe the path does not take (the stub) reaches one radius past
        the other pipe's wall, open."""
        radius, wall = piece.diameter / 2, self.wall_radius(piece)
        centre = _add(piece.entry.origin, piece.entry.axes[0], radius)
        if piece.spec['enter'] == 'branch':          # the run across, the path leaving along it
            run_axes, run_span = piece.exit.axes, (-2 * radius, radius)
            branch_axis, branch_end = tuple(-c for c in piece.entry.axes[0]), radius
        elif tee_leaves_by(piece.spec) == 'branch':  # the run ahead, the path leaving by the branch
            run_axes, run_span = piece.entry.axes, (-radius, 2 * radius)
            branch_axis, branch_end = piece.exit.axes[0], radius
        else:                                        # straight on along the run
            run_axes, run_span = piece.entry.axes, (-radius, radius)
            branch_axis, branch_end = piece.stub.axes[0], 2 * radius
        start = _add(centre, run_axes[0], run_span[0])
        length = run_span[1] - run_span[0]
        hole_mid = -run_span[0]

        def run_spans(radial):
            facing = _dot(radial, branch_axis)
            if facing <= 0:
                return [(0.0, length)]
            return [(0.0, hole_mid - wall * facing), (hole_mid + wall * facing, length)]
        self.tube(start, run_axes, wall, run_spans)
        branch_axes = _frame_along(branch_axis, run_axes[0])
        self.tube(centre, branch_axes, wall,
                  lambda r: [(self._clear_of_run(wall, _dot(r, run_axes[0])), branch_end)])

    def _clear_of_run(self, radius, along_run):
        """Where a branch wall box must start (m from the run's axis along the
        branch) so that no part of it lies inside the run: ``along_run`` is
        its radial direction's component along the run's axis. The wall
        meets the run at radius * |along_run| at the box's middle line, but
        a flat box is ``half_width`` wide, and toward one of its long edges
        it meets the run further out (by up to 5 mm at 45 deg in 90 mm): cut
        at the middle, that edge stood inside the run as a step at the
        hole's rim, square to a wheel rolling over it (twin: lying on its
        side the front V's apex wheel stalled on it 3 mm into the hole of a
        T-joint open to that side)."""
        half_width = radius * math.tan(math.pi / self.segments) + self.thickness / 2
        across = math.sqrt(max(0.0, 1.0 - along_run * along_run))
        nearest = max(0.0, radius * across - half_width * abs(along_run))
        return math.sqrt(max(0.0, radius * radius - nearest * nearest))

    def _floor(self, world, obstacle):
        index, frame = world.locate(obstacle['at_m'])
        return self.wall_radius(world.pieces[index]), frame

    def _obstacle_step(self, world, obstacle):
        radius, frame = self._floor(world, obstacle)
        height = obstacle['height_mm'] / 1000.0
        depth = radius - height / 2
        centre = _add(_add(frame.origin, frame.axes[0], 0.1), frame.axes[2], -depth)
        self.box(centre, frame.axes[0], frame.axes[1], (0.1, radius * 0.6, height / 2), 'step')

    def _obstacle_reduction(self, world, obstacle):
        _, frame = self._floor(world, obstacle)
        length = obstacle.get('length_mm', 50) / 1000.0
        self.tube(frame.origin, frame.axes, obstacle['diameter_mm'] / 2000.0, lambda r: [(0.0, length)])

    def _obstacle_debris(self, world, obstacle):
        """A loose box that falls to the floor, where the robot may push it."""
        radius, frame = self._floor(world, obstacle)
        half = obstacle['size_mm'] / 2000.0
        body = ET.SubElement(self.parent, 'body', name='debris%d' % self.count,
                             pos=_fmt(_add(frame.origin, frame.axes[2], -(radius - half - 0.002))))
        ET.SubElement(body, 'freejoint')
        ET.SubElement(body, 'geom', type='box', size=_fmt((half, half, half)), mass='0.005',
                      name='debris_geom%d' % self.count, contype='1', conaffinity='1', **{'class': PIPE_CLASS})
        self.count += 1


def _frame_along(x_axis, hint):
    """Right-handed frame rows with ``x_axis`` first and ``hint`` as y."""
    y = hint
    z = (x_axis[1] * y[2] - x_axis[2] * y[1], x_axis[2] * y[0] - x_axis[0] * y[2],
         x_axis[0] * y[1] - x_axis[1] * y[0])
    return (x_axis, y, z)
