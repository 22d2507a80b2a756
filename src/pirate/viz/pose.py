"""Where the robot's base frame lies in the pipe, from the IMU roll (pure).

The report's orientation (Fig 4.7) is the rear part's roll about the pipe
axis: pi/2 upright, 0 lying on its right side, pi lying on its left. In the
'pipe' frame (REP 103: x along the pipe, the robot's forward; y left; z up)
lying on the right side is a roll of +pi/2 about x (the robot's left side
turns up), so the REP roll is pi/2 minus the orientation.

The base link (the rotational module's rear half, pirate.viz.urdf_gen) has
its wheel on the robot's -z wall when the rear part is clamped, so the base
frame sits (Dp - D_omega)/2 from the pipe axis towards that wall: the model
then touches the pipe as the clamped robot does. No ROS import here.
"""
import math

from pirate.viz.urdf_gen import WHEEL_DIAMETER


def rep_roll(orientation):
    """REP 103 roll about the pipe axis (rad) for a Fig 4.7 orientation (rad)."""
    return math.pi / 2 - orientation


def quaternion_about_x(angle):
    """(x, y, z, w) of a rotation by ``angle`` rad about the x axis."""
    return (math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2))


def base_in_pipe(orientation, pipe_diameter_mm):
    """((x, y, z) m, (qx, qy, qz, qw)) of the base frame in the pipe frame.

    Raises ValueError for a non-finite orientation or a pipe narrower than
    a wheel, so the caller can log it once and keep the last pose.
    """
    if not math.isfinite(orientation):
        raise ValueError('orientation %r is not finite' % (orientation,))
    diameter = pipe_diameter_mm / 1000.0
    if not diameter > WHEEL_DIAMETER:
        raise ValueError('pipe diameter %r mm is not wider than a wheel (%g mm)'
                         % (pipe_diameter_mm, WHEEL_DIAMETER * 1000))
    roll = rep_roll(orientation)
    offset = (diameter - WHEEL_DIAMETER) / 2
    # The robot's -z axis rotated by the roll about x: (0, sin r, -cos r).
    return ((0.0, offset * math.sin(roll), -offset * math.cos(roll)),
            quaternion_about_x(roll))


def cylinder_along_x():
    """(x, y, z, w) turning a cylinder's axis (its z) onto x: pi/2 about y."""
    return (0.0, math.sin(math.pi / 4), 0.0, math.cos(math.pi / 4))
