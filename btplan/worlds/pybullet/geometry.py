"""Plain-geometry helpers shared by the world and its skills (no simulator calls here)."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.scene import Point

DIRECTIONS = 16
"""Candidate approach and drop directions around a point, every 22.5 degrees."""


def distance(a: Point | Pose2, b: Point | Pose2) -> float:
    """Distance in the floor plane, in metres; z and yaw are ignored, so poses and points mix."""
    return math.hypot(a[0] - b[0], a[1] - b[1])


def ring(center: Point, radius: float, first: float = 0.0) -> list[Point]:
    """Points on a circle around `center`, starting at angle `first`, counter-clockwise."""
    return [(center[0] + radius * math.cos(first + 2 * math.pi * k / DIRECTIONS),
             center[1] + radius * math.sin(first + 2 * math.pi * k / DIRECTIONS))
            for k in range(DIRECTIONS)]


def facing(at: Point, target: Point) -> Pose2:
    """The base pose at `at` turned towards `target`."""
    return (at[0], at[1], math.atan2(target[1] - at[1], target[0] - at[0]))


def clearance(point: Point, path: Sequence[Pose2]) -> float:
    """Smallest distance from `point` to the waypoints of `path` (inf for an empty path)."""
    return min((distance(point, q) for q in path), default=math.inf)


def grid(low: Point, high: Point, step: float) -> Iterable[Point]:
    """Points of a regular grid inside the rectangle, row by row (deterministic order)."""
    nx = max(1, int((high[0] - low[0]) / step))
    ny = max(1, int((high[1] - low[1]) / step))
    for j in range(ny + 1):
        for i in range(nx + 1):
            yield (round(low[0] + i * (high[0] - low[0]) / nx, 4),
                   round(low[1] + j * (high[1] - low[1]) / ny, 4))
