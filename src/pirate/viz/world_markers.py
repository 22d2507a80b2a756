"""What RViz draws of the physics twin's world and true robot (pure).

The pipe network (pirate.world.network) as translucent cylinders: every
straight, both legs of a mitre bend, a T-joint's run and branch, end caps
as thin discs, each defect as a sphere on the wall. The robot at its true pose from the physics (the ground
truth topic, one pose per module in pirate.sim.twin_robot.TRUTH_BODIES order) as
boxes of the twin's module size with their wheels. Plain tuples out; the
node (pirate.viz.world_node) turns them into markers. No ROS import.
"""
import math

from pirate.world import network

#: Shape = (kind 'cylinder'|'shell'|'wheel'|'defect', centre xyz, quaternion xyzw, scale xyz).
CAP_THICKNESS_M = 0.004
DEFECT_MIN_M = 0.015        # a defect's marker is never smaller than this (a 2 mm crack must show)


def _add(a, b, scale=1.0):
    return tuple(x + scale * y for x, y in zip(a, b))


def z_to(axis):
    """Quaternion (x, y, z, w) turning +z onto the unit vector ``axis``."""
    x, y, z = axis
    if z < -1 + 1e-9:
        return (1.0, 0.0, 0.0, 0.0)
    w = 1.0 + z
    norm = math.sqrt(w * w + y * y + x * x)
    return (-y / norm, x / norm, 0.0, w / norm)


def _tube(start, axis, length, diameter):
    return ('cylinder', _add(start, axis, length / 2), z_to(axis), (diameter, diameter, length))


def pipe_shapes(world):
    """Cylinders of every piece of ``world``."""
    shapes = []
    for piece in world.pieces:
        d, x_in = piece.diameter, piece.entry.axes[0]
        if piece.kind == 'straight':
            shapes.append(_tube(piece.entry.origin, x_in, piece.length, d))
        elif piece.kind == 'cap':
            shapes.append(_tube(piece.entry.origin, x_in, CAP_THICKNESS_M, d + 2 * CAP_THICKNESS_M))
        else:
            corner = _add(piece.entry.origin, x_in, d / 2)
            shapes.append(_tube(piece.entry.origin, x_in, d / 2, d))
            if network.turns_at_corner(piece):
                shapes.append(_tube(corner, piece.exit.axes[0], d / 2, d))
            else:
                shapes.append(_tube(corner, x_in, d / 2, d))
            if piece.stub is not None:
                shapes.append(_tube(corner, piece.stub.axes[0], d, d))
    return shapes


def defect_shapes(world):
    """A sphere on the wall at each defect of ``world``, as large as the defect."""
    shapes = []
    for defect in world.defects:
        piece = world.pieces[defect.piece]
        radial = network.clock_direction(piece.entry.axes, defect.clock)
        centre = _add(_add(piece.entry.origin, piece.entry.axes[0], defect.at), radial, piece.diameter / 2)
        size = max(defect.size, DEFECT_MIN_M)
        shapes.append(('defect', centre, (0.0, 0.0, 0.0, 1.0), (size, size, size)))
    return shapes


def _rotate(q_wxyz, v):
    """Vector ``v`` rotated by the unit quaternion (w, x, y, z)."""
    w, x, y, z = q_wxyz
    u = (x, y, z)
    uv = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    uuv = (u[1] * uv[2] - u[2] * uv[1], u[2] * uv[0] - u[0] * uv[2], u[0] * uv[1] - u[1] * uv[0])
    return tuple(v[i] + 2 * (w * uv[i] + uuv[i]) for i in range(3))


def robot_shapes(poses, directions, geometry):
    """Module shells (round, about the module's axis) and wheel discs at the true poses.

    ``poses``: [(xyz, wxyz)] per module (body origin = its joint);
    ``directions``: +-1 a module reaching forward (+) or back (-) from its
    joint, with the joint's wheel; +-2 a half of the rotational module
    (no wheel at the rotation joint); ``geometry``: config/twin.yaml's
    geometry section.
    """
    length = geometry['module_length_m']
    diameter = 2 * geometry['body_radius_m']
    wheel_d = geometry['wheel_diameter_m']
    shapes = []
    for (pos, quat), direction in zip(poses, directions):
        extent = length / 2 if abs(direction) == 2 else length
        centre = _add(pos, _rotate(quat, (direction / abs(direction) * extent / 2, 0.0, 0.0)))
        along = _rotate(quat, (1.0, 0.0, 0.0))
        shapes.append(('shell', centre, z_to(along), (diameter, diameter, extent)))
        if abs(direction) == 1:                  # a wheel on this module's joint
            axle = _rotate(quat, (0.0, 1.0, 0.0))
            shapes.append(('wheel', pos, z_to(axle), (wheel_d, wheel_d, 2 * geometry['wheel_half_width_m'])))
    return shapes
