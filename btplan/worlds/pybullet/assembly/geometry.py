"""Quaternions (x, y, z, w, as PyBullet writes them) and the axes of a rotated frame.

Plain arithmetic, no simulator: the skills turn a hand from pointing down to pointing
at the other arm and back, and need the axes of a part from its orientation.
"""

from __future__ import annotations

import math

Quat = tuple[float, float, float, float]
Vec = tuple[float, float, float]
IDENTITY: Quat = (0.0, 0.0, 0.0, 1.0)


def axis_x(q: Quat) -> Vec:
    """The frame's x axis in world coordinates (the rotation matrix's first column).

    For a part, the direction of its length.
    """
    x, y, z, w = q
    return (1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w))


def axis_y(q: Quat) -> Vec:
    """The frame's y axis in world coordinates (the second column): across a part's width."""
    x, y, z, w = q
    return (2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w))


def axis_z(q: Quat) -> Vec:
    """The frame's z axis in world coordinates (the third column); `rotate` uses all three."""
    x, y, z, w = q
    return (2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y))


def down(yaw: float) -> Quat:
    """A hand pointing at the table, turned by `yaw` (roll pi, then yaw)."""
    return (math.cos(yaw / 2), math.sin(yaw / 2), 0.0, 0.0)


def multiply(a: Quat, b: Quat) -> Quat:
    """The rotation b, then a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def inverse(q: Quat) -> Quat:
    """The opposite rotation of a unit quaternion (its conjugate); only right for length 1."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quat, v: Vec) -> Vec:
    """`v`, given in the frame `q` describes, expressed in world coordinates."""
    ex, ey, ez = axis_x(q), axis_y(q), axis_z(q)
    return (ex[0] * v[0] + ey[0] * v[1] + ez[0] * v[2],
            ex[1] * v[0] + ey[1] * v[1] + ez[1] * v[2],
            ex[2] * v[0] + ey[2] * v[1] + ez[2] * v[2])


def cross(a: Vec, b: Vec) -> Vec:
    """The cross product a x b (right-handed): perpendicular to both, |a||b| sin(angle) long."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def turn_between(a: Vec, b: Vec) -> Quat:
    """The shortest rotation taking direction `a` to direction `b` (both unit length)."""
    axis = cross(a, b)
    n = math.sqrt(sum(c * c for c in axis))
    dot = max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b))))
    half = math.atan2(n, dot) / 2
    if n < 1e-9:
        if dot > 0:
            return IDENTITY
        axis = cross(a, (0.0, 0.0, 1.0)) if abs(a[2]) < 0.9 else cross(a, (1.0, 0.0, 0.0))
        n, half = math.sqrt(sum(c * c for c in axis)), math.pi / 2
    s = math.sin(half) / n
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(half))


def quat_from_axes(x: Vec, y: Vec, z: Vec) -> Quat:
    """The orientation whose frame has the (orthonormal) axes x, y, z."""
    m00, m11, m22 = x[0], y[1], z[2]
    trace = m00 + m11 + m22
    if trace > 0:
        s = math.sqrt(trace + 1.0) * 2
        return ((y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s, 0.25 * s)
    if m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        return (0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s, (y[2] - z[1]) / s)
    if m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        return ((y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s, (z[0] - x[2]) / s)
    s = math.sqrt(1.0 + m22 - m00 - m11) * 2
    return ((z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s, (x[1] - y[0]) / s)
