"""Where things go: approach poses, spots to put a cube down, poses off a path.

These are the world's samplers for continuous values. They search a fixed set of
candidates (a ring around a point, a grid over a region) in a fixed order, so the same
scene always gives the same answer, and they use PyBullet only through the world's
collision queries. Refinement (refine.py) asks them for values.
"""

from __future__ import annotations

from btplan.worlds.pybullet.geometry import clearance, distance, facing, grid, ring
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.scene import Point
from btplan.worlds.pybullet.state import KEY_DIGITS, MISSED, SceneState

GRID = 0.25  # metres between candidate placement poses
ARM_NEAR, ARM_FAR = 0.45, 0.68
"""Distances from the base's centre at which the arm reaches the floor (a ring in front)."""


def approach_pose(world: SceneState, name: str, avoid_cubes: bool = True) -> Pose2 | None:
    """A collision-free base pose next to a location, facing it, closest to the robot."""
    target = world.location(name)
    missed = world.missed_poses(name)
    asked = ("approach", name, avoid_cubes, target, len(missed))
    if asked in world.sim.memo:  # asked again before anything moved
        return world.sim.memo[asked]  # type: ignore[return-value]
    world.sim.memo[asked] = pose = _approach(world, target, name, avoid_cubes, missed)
    return pose


def _approach(world: SceneState, target: Point, name: str, avoid_cubes: bool,
              missed: list[Pose2]) -> Pose2 | None:
    reach = world.scene.robot_radius + world.scene.cube_size / 2 + 0.08
    cubes = world.floor_cubes(name, world.held) if avoid_cubes else []
    # The free spots depend on where the target and the other cubes are: asked every tick
    # for every path, they are only searched again when something moved (by 0.1 mm).
    key = ("approach", tuple(round(v, KEY_DIGITS) for v in target),
           tuple((c, world.rounded(c)) for c in cubes))
    spots = world.queries.get(key)
    if not isinstance(spots, list):
        spots = [q for q in ring(target, reach) if world.sim.base_free(q[0], q[1], cubes, 0.02)]
        world.remember(key, spots)
    # Sides the arm already failed from are left out, the nearest untried side first.
    spots = [q for q in spots if all(distance(q, m) > MISSED for m in missed)]
    if not spots:
        return None
    best = min(spots, key=lambda q: (round(distance(q, world.base), 3), q))
    return facing(best, target)


def place_spot(world: SceneState, place: str) -> Point | None:
    """Where Place puts a cube: the free spot of a region nearest the robot, or the pose."""
    if place in world.poses:
        return world.poses[place]
    region = world.scene.region(place)
    if region is None:
        return None
    cubes = world.floor_cubes(world.held)
    spots = [q for q in grid(region.low, region.high, 0.15)
             if region.contains(*q, margin=0.1) and world.sim.cube_fits(q[0], q[1], cubes)]
    reach = [q for q in spots if ARM_NEAR <= distance(q, world.base) <= ARM_FAR]
    return min(reach or spots, key=lambda q: (round(distance(q, world.base), 3), q), default=None)


def drop_spot(world: SceneState) -> Point | None:
    """Beside the robot, off every known path when possible: a dropped cube is in no one's way."""
    cubes = world.floor_cubes(world.held)
    reach = world.scene.robot_radius + world.scene.cube_size / 2 + 0.05
    spots = [q for q in ring(world.base[:2], reach, world.base[2])
             if world.sim.cube_fits(q[0], q[1], cubes) and not world.drop_missed(q)]
    paths = [t.path for t in world.trajectories.values() if t.path]
    keep = world.scene.robot_radius + world.scene.cube_size

    def score(q: Point) -> tuple[int, float]:
        worst = min((clearance(q, p) for p in paths), default=10.0)
        return (0 if worst > keep else 1, -round(min(worst, 10.0), 3))

    return min(spots, key=score, default=None)


def aside_spot(world: SceneState, paths: list[tuple[Pose2, ...]], pose: str | None = None
               ) -> Point | None:
    """A spot to put an obstacle: in an `aside` region if the scene has one, off `paths`.

    `pose`: the name the spot is for, when an existing pose is sampled again (its own
    old spot does not count as taken).
    """
    regions = [r for r in world.scene.regions if r.aside]
    x0, x1, y0, y1 = world.scene.bounds
    inset = 0.1  # a cube put down by a real hand lands within a few millimetres of the spot
    areas = [((r.low[0] + inset, r.low[1] + inset), (r.high[0] - inset, r.high[1] - inset))
             for r in regions] or [((x0, y0), (x1, y1))]
    best: tuple[float, Point] | None = None
    for low, high in areas:
        for q in grid(low, high, GRID):
            if not aside_fits(world, q, paths, pose):
                continue
            score = round(distance(q, world.base), 3)
            if best is None or (score, q) < best:
                best = (score, q)
    return None if best is None else best[1]


def aside_fits(world: SceneState, q: Point, paths: list[tuple[Pose2, ...]],
               pose: str | None = None) -> bool:
    """Off every path in `paths`, away from other poses and regions, and free of cubes."""
    keep = world.scene.robot_radius + world.scene.cube_size + 0.1
    if any(r.contains(*q, margin=-0.2) for r in world.scene.regions if not r.aside):
        return False
    if any(clearance(q, path) <= keep for path in paths):
        return False
    if any(distance(q, t) < 0.3 for name, t in world.poses.items() if name != pose):
        return False
    return world.sim.cube_fits(q[0], q[1], world.floor_cubes(world.held), 0.15)
