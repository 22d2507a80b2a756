"""A position along a pipe map as a 3-D pose (for RViz and ground truth checks).

Pure: the quaternion of a frame whose axes (rows, world coordinates) are
those :meth:`pirate.world.network.Network.locate` gives.
"""
import math


def quaternion_of_axes(axes):
    """(x, y, z, w) of the rotation whose columns are ``axes`` (x, y, z rows)."""
    (m00, m10, m20), (m01, m11, m21), (m02, m12, m22) = axes
    trace = m00 + m11 + m22
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        return ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    if m00 >= m11 and m00 >= m22:
        s = 2.0 * math.sqrt(1.0 + m00 - m11 - m22)
        return (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    if m11 >= m22:
        s = 2.0 * math.sqrt(1.0 + m11 - m00 - m22)
        return ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    s = 2.0 * math.sqrt(1.0 + m22 - m00 - m11)
    return ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)


def pose_along(network, along_m):
    """(position xyz in m, quaternion xyzw) of the path's axis at ``along_m``."""
    _, frame = network.locate(along_m)
    return frame.origin, quaternion_of_axes(frame.axes)


def path_points(network, from_m, to_m, step_m=0.02):
    """Points (xyz, m) on the path's axis from ``from_m`` to ``to_m`` (either
    way), every ``step_m`` and at both ends: a route drawn as a line."""
    count = max(1, int(abs(to_m - from_m) / step_m))
    return [network.locate(from_m + (to_m - from_m) * i / count)[1].origin for i in range(count + 1)]
