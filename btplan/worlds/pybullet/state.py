"""The scene state at the bottom of the PyBullet world: where the robot and the cubes are.

Everything above it (samplers, routes, skills, agents, the recorder and the world the
tree ticks against) reads and changes the scene through this one object, and nothing
here knows about them: the import graph of the backend has no circle.
"""

from __future__ import annotations

from btplan.errors import WorldError
from btplan.model import Task
from btplan.worlds.pybullet.geometry import clearance, distance
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.paths import Trajectory
from btplan.worlds.pybullet.scene import Point, Scene
from btplan.worlds.pybullet.sim import Sim


class SceneState:
    """The robot's base, the cubes, the named trajectories and poses, and the PyBullet client."""

    def __init__(self, task: Task, scene: Scene, gui: bool = False) -> None:
        self.task, self.scene = task, scene
        self.cube_names = tuple(sorted(c.name for c in scene.cubes))
        self.on_floor: dict[str, Point | None] = {c.name: c.at for c in scene.cubes}
        self.held: str | None = None
        self.clearing_now: str | None = None  # the cube a running ClearPath carries
        self.handled = 0  # cubes the robot grasped or put down so far
        self.base: Pose2 = scene.start
        self.trajectories: dict[str, Trajectory] = {}
        self.poses: dict[str, Point] = {}
        self.check_objects()
        self.sim = Sim(scene, gui)  # after the checks: a refused scene leaves no connection open

    def check_objects(self) -> None:
        known = set(self.cube_names) | {r.name for r in self.scene.regions}
        poses = set(self.task.objects_of(self.type_of("pose")))
        for name in self.task.objects_of(self.type_of("location")):
            if name not in known and name not in poses:
                raise WorldError(f"{name!r} is a location in the problem but not in the scene "
                                 f"{self.scene.path}; add it as a [[cube]] or [[region]]")

    def type_of(self, wanted: str) -> str:
        return wanted if wanted in self.task.domain.type_parents else "object"

    def present(self, cube: str) -> bool:
        return self.held == cube or self.on_floor.get(cube) is not None

    def floor_cubes(self, *excluded: str | None) -> list[str]:
        return [c for c in self.cube_names if self.on_floor.get(c) is not None and c not in excluded]

    def location(self, name: str) -> Point:
        """Where a location is now: a cube's position, a region's centre or a sampled pose."""
        if name in self.on_floor:
            if self.held == name:
                return self.sim.gripper_point()
            at = self.on_floor[name]
            if at is None:
                raise WorldError(f"cube {name!r} is not in the scene")
            return at
        region = self.scene.region(name)
        if region is not None:
            return region.center
        if name in self.poses:
            return self.poses[name]
        raise WorldError(f"{name!r} is not a cube, region or pose of this scene")

    def is_near(self, name: str) -> bool:
        if name in self.on_floor and not self.present(name):
            return False
        return distance(self.base, self.location(name)) <= self.scene.near

    def on(self, cube: str, place: str) -> bool:
        at = self.on_floor.get(cube)
        if at is None:
            return False
        region = self.scene.region(place)
        if region is not None:
            return region.contains(*at)
        if place in self.poses:
            return distance(at, self.poses[place]) <= 0.1
        return False

    def move_base(self, pose: Pose2) -> None:
        self.base = pose
        self.sim.set_robot(pose, self.held)

    def grasp(self, cube: str) -> None:
        self.handled += 1
        self.held = cube
        self.on_floor[cube] = None
        self.sim.set_robot(self.base, cube)

    def release(self, spot: Point) -> None:
        """Put the held cube down; obstacles put off a path stop blocking it."""
        cube = self.held
        if cube is None:
            return
        self.handled += 1
        self.held = None
        self.put(cube, spot)

    def put(self, cube: str, spot: Point | None) -> None:
        """Set a cube on the floor (None takes it out of the scene); agents use this too."""
        if self.held == cube:
            self.held = None
        self.on_floor[cube] = spot
        self.sim.place_cube(cube, spot)
        if spot is not None:
            for traj in self.trajectories.values():
                if cube in traj.clearing and not self.on_path(cube, traj.path, 0):
                    traj.clearing.discard(cube)
        else:
            for traj in self.trajectories.values():
                traj.clearing.discard(cube)

    def layout(self) -> tuple[object, ...]:
        """What the robot itself changed: a path planned before it moved a cube is stale.

        A cube moved by someone else is deliberately not part of it: the stored path is
        checked against it, so an obstacle that appears on the way blocks the path.
        """
        return (self.held, self.handled)

    def on_path(self, cube: str, path: tuple[Pose2, ...], start: int) -> bool:
        at = self.on_floor.get(cube)
        if at is None or not path:
            return False
        reach = self.scene.robot_radius + self.scene.cube_size
        rest = path[start:]
        if clearance(at, rest) > reach:
            return False
        return any(self.sim.base_hits(q[0], q[1], [cube]) for q in rest[::2] + rest[-1:])

    def path_blockers(self, traj: Trajectory, start: int = 0) -> set[str]:
        """Cubes on the floor on the rest of the path, and cleared obstacles still in hand."""
        found = {c for c in self.floor_cubes(traj.target, self.held)
                 if self.on_path(c, traj.path, start)}
        if self.held is not None and self.held in traj.clearing:
            found.add(self.held)
        return found

    def blockers(self, traj: Trajectory) -> set[str]:
        if not traj.path:
            return {"(no path)"}
        return self.path_blockers(traj)

    def close(self) -> None:
        self.sim.close()
