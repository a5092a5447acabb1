"""The scene state at the bottom of the PyBullet world: where the robot and the cubes are.

Everything above it (samplers, routes, skills, agents, the recorder and the world the
tree ticks against) reads and changes the scene through this one object, and nothing
here knows about them: the import graph of the backend has no circle.
"""

from __future__ import annotations

import math

from btplan.errors import InputError, Span, WorldError
from btplan.model import Task
from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.paths import Trajectory
from btplan.worlds.pybullet.scene import Point, Scene
from btplan.worlds.pybullet.sim import HZ, Sim

REST_HEIGHT = 0.01   # metres above its resting height a cube on the floor may be
REST_SPEED = 0.25    # m/s: slower than this, a cube on the floor has landed (it may still settle)
LIFTED = 0.004       # metres above its resting height a held cube must be
QUERIES_KEPT = 5000  # collision query answers kept before they are all forgotten
KEY_DIGITS = 4       # cube positions in the keys of those answers: to 0.1 mm
MOVED = 0.02         # metres a cube must move before a failed reach of it is forgotten
MISSED = 0.1         # metres around a base pose a grasp failed from: the same side of the cube
SAME_SPOT = 0.05     # metres between two spots to put a cube down that count as one


class SceneState:
    """The robot, the cubes, the named trajectories and poses, and the PyBullet client.

    Where a cube is and whether the robot holds it are read from the simulation each
    time they are asked; the only bookkeeping is what the planner named (trajectories,
    poses) and how often the robot handled a cube (which makes planned paths stale).
    """

    def __init__(self, task: Task, scene: Scene, gui: bool = False) -> None:
        self.task, self.scene = task, scene
        self.cube_names = tuple(sorted(c.name for c in scene.cubes))
        self.handled = 0  # cubes the robot grasped or put down so far
        self.carried: set[str] = set()  # cubes in an external agent's hand, out of reach
        self.releasing: str | None = None  # the cube a running put-down is letting go of
        self.failure = ""  # why the running skill is failing, as it says (skills.refuse)
        self.out_of_reach: dict[str, Point] = {}
        """Cubes the arm failed to reach from where the base stands, and where they were:
        not `near` until the robot drives up to them again (or they move)."""
        self.missed_from: dict[str, tuple[Point, list[Pose2]]] = {}
        """Base poses from which a grasp of a cube failed, and where the cube was then: the
        approach sampler offers other sides of the cube, so that MoveTo does not bring the
        robot back to a pose where Pick is known to fail."""
        self.missed_drops: list[tuple[Pose2, Point]] = []
        """Spots beside the base a held cube could not be lowered onto (no collision-free
        reach), and the base pose each was tried from: Drop offers other spots from there,
        where it used to pick the same spot, and fail, every time it was started."""
        self.trajectories: dict[str, Trajectory] = {}
        self.poses: dict[str, Point] = {}
        self.queries: dict[object, object] = {}
        """Answers of collision queries, keyed by the exact positions they depend on: a
        cube at rest and a path not planned again give the same answer every tick."""
        self.check_objects()
        self.sim = Sim(scene, gui)  # after the checks: a refused scene leaves no connection open

    @property
    def base(self) -> Pose2:
        """The base's pose: x, y in metres and yaw in radians, in the world frame."""
        return self.sim.pose

    @property
    def seconds(self) -> float:
        """Simulated time: physics steps so far."""
        return self.sim.steps / HZ

    @property
    def held(self) -> str | None:
        """The cube between the closed fingers, both touching it (from the scene, not a flag)."""
        memo = self.sim.memo
        if "held" not in memo:
            robot = self.sim.robot
            tip = robot.tip()
            memo["held"] = next((name for name in self.cube_names
                                 if math.dist(self.sim.cube_position(name), tip) < 0.08
                                 and robot.holds(self.sim.cubes[name])), None)
        held = memo["held"]
        return held if isinstance(held, str) else None

    def lifted(self, cube: str) -> bool:
        """In the hand and off the floor: what Pick achieves and `holding(c)` means."""
        z = self.sim.cube_position(cube)[2]
        return z > self.scene.cube_size / 2 + LIFTED and self.held == cube

    def in_hand(self, cube: str | None = None) -> str | None:
        """The cube `holding` speaks of (`cube`, if given and in hand), or None.

        A cube is in hand once lifted, and stays so while a Place or Drop lets go of it
        and it settles: the action's effects count when it ends. Fingers closing on a cube
        still on the floor do not hold it yet.
        """
        found = self.releasing
        if found is None:
            held = self.held
            found = held if held is not None and self.lifted(held) else None
        return found if cube is None or found == cube else None

    def bookkeeping(self) -> tuple[object, ...]:
        """Everything here that is not read from the simulation (paths are compared by
        value, cheaply: an unchanged path is the same object)."""
        paths = tuple((t.name, t.target, t.path, t.goal, frozenset(t.clearing), t.executing,
                       t.layout) for t in self.trajectories.values())
        return (self.handled, self.releasing, frozenset(self.carried),
                tuple(self.out_of_reach.items()), tuple(self.poses.items()), paths,
                tuple((c, len(m[1])) for c, m in self.missed_from.items()),
                len(self.missed_drops))

    def check_objects(self) -> None:
        """Refuse a problem location that is no cube or region of the scene, nor a pose object.

        Checked before the simulation starts, with the scene file's name in the error.
        """
        known = set(self.cube_names) | {r.name for r in self.scene.regions}
        poses = set(self.task.objects_of(self.type_of("pose")))
        for name in self.task.objects_of(self.type_of("location")):
            if name not in known and name not in poses:
                raise InputError(f"{name!r} is a location in the problem but not in this scene",
                                 Span(self.scene.path, 1, 1),
                                 "add it as a [[cube]] or a [[region]]")

    def type_of(self, wanted: str) -> str:
        """`wanted` if the domain declares that type, else `object`: a domain may leave it out."""
        return wanted if wanted in self.task.domain.type_parents else "object"

    def present(self, name: str) -> bool:
        """A cube in the scene and not in an agent's hand; any other location is always there."""
        if name not in self.sim.cubes:
            return True
        return name not in self.carried and self.sim.cube_position(name)[2] > -1.0

    def floor_cubes(self, *excluded: str | None) -> list[str]:
        """Cubes in the scene and not in the hand, except `excluded`."""
        skip = {*excluded, self.held}
        return [c for c in self.cube_names if c not in skip and self.present(c)]

    def resting(self, cube: str) -> bool:
        """On the floor and still: where a put-down cube came to rest."""
        z = self.sim.cube_position(cube)[2]
        return (-1.0 < z <= self.scene.cube_size / 2 + REST_HEIGHT
                and self.sim.cube_speed(cube) < REST_SPEED)

    def location(self, name: str) -> Point:
        """Where a location is now: a cube's position, a region's centre or a sampled pose."""
        if name in self.sim.cubes:
            x, y, z = self.sim.cube_position(name)
            if z < -1.0:
                raise WorldError(f"cube {name!r} is not in the scene")
            return (x, y)
        region = self.scene.region(name)
        if region is not None:
            return region.center
        if name in self.poses:
            return self.poses[name]
        raise WorldError(f"{name!r} is not a cube, region or pose of this scene")

    def is_near(self, name: str) -> bool:
        """Whether the base is within `near` metres of the location, in the plane.

        A cube out of the scene is never near, nor one the arm just failed to reach from here
        and that has not moved since (so the tree drives up to it again).
        """
        if name in self.sim.cubes and not self.present(name):
            return False
        at = self.location(name)
        missed = self.out_of_reach.get(name)
        if missed is not None and distance(missed, at) < MOVED:
            return False
        return distance(self.base, at) <= self.scene.near

    def missed_reach(self, cube: str) -> None:
        """The arm cannot grasp `cube` from where the base stands: not `near` from here."""
        at = self.location(cube)
        self.out_of_reach[cube] = at
        known = self.missed_from.get(cube)
        poses = known[1] if known is not None and distance(known[0], at) < MOVED else []
        if all(distance(self.base, m) > MISSED for m in poses):
            poses = [*poses, self.base]  # a side tried again adds nothing to go round on
        self.missed_from[cube] = (at, poses)

    def missed_drop(self, spot: Point) -> None:
        """The arm could not put the held cube down at `spot` from where the base stands."""
        self.missed_drops.append((self.base, spot))

    def drop_missed(self, spot: Point) -> bool:
        """A put-down at `spot` (or within SAME_SPOT of it) failed from here before."""
        return any(distance(base, self.base) <= MISSED and distance(at, spot) <= SAME_SPOT
                   for base, at in self.missed_drops)

    def missed_poses(self, name: str) -> list[Pose2]:
        """Base poses a grasp of `name` failed from, while it has not moved since."""
        known = self.missed_from.get(name)
        if known is None or name not in self.sim.cubes or not self.present(name) \
                or distance(known[0], self.location(name)) >= MOVED:
            return []
        return known[1]

    def on(self, cube: str, place: str) -> bool:
        """`cube` came to rest inside region `place`, or at pose `place`."""
        region = self.scene.region(place)
        if (region is None and place not in self.poses) or not self.resting(cube):
            return False
        at = self.location(cube)
        if region is not None:
            return region.contains(*at)
        if place in self.poses:
            return distance(at, self.poses[place]) <= 0.1
        return False

    def move_base(self, pose: Pose2) -> None:
        """Put the base at `pose`, kinematically; drives call it on every physics substep."""
        self.sim.set_robot(pose)

    def released(self, cube: str) -> None:
        """A cube the robot put down off a path no longer blocks it once out of the hand."""
        self.handled += 1
        for traj in self.trajectories.values():
            if cube in traj.clearing and not self.on_path(cube, traj.path, 0):
                traj.clearing.discard(cube)

    def put(self, cube: str, spot: Point | None) -> None:
        """Teleport a cube to the floor (None takes it out of the scene): tests and events."""
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
        """Whether the robot's disc touches `cube` on `path` from waypoint `start` on.

        Every second waypoint and the last are tested; False for an empty path or a cube out
        of the scene. Answers are kept per path object and rounded cube position.
        """
        if not path or not self.present(cube):
            return False
        position = self.sim.cube_position(cube)
        key = ("on_path", id(path), start, cube, self.rounded(cube))
        known = self.queries.get(key)
        if isinstance(known, tuple) and known[0] is path:  # the same path, not a reused id
            return bool(known[1])
        found = self._on_path(position[0], position[1], cube, path, start)
        self.remember(key, (path, found))
        return found

    def _on_path(self, x: float, y: float, cube: str, path: tuple[Pose2, ...], start: int
                 ) -> bool:
        """The collision check of `on_path`, after two cheap tests that the cube is far:
        outside the whole path's bounding box, then farther than `reach` from every waypoint."""
        reach = self.scene.robot_radius + self.scene.cube_size
        x0, x1, y0, y1 = self._box(path)
        if not (x0 - reach <= x <= x1 + reach and y0 - reach <= y <= y1 + reach):
            return False
        rest, square = path[start:], reach * reach
        if all((q[0] - x) ** 2 + (q[1] - y) ** 2 > square for q in rest):
            return False
        return any(self.sim.base_hits(q[0], q[1], [cube]) for q in rest[::2] + rest[-1:])

    def _box(self, path: tuple[Pose2, ...]) -> tuple[float, float, float, float]:
        key = ("box", id(path))
        known = self.queries.get(key)
        if isinstance(known, tuple) and known[0] is path:
            return known[1]  # type: ignore[no-any-return]
        xs, ys = [q[0] for q in path], [q[1] for q in path]
        box = (min(xs), max(xs), min(ys), max(ys))
        self.remember(key, (path, box))
        return box

    def rounded(self, cube: str) -> tuple[float, ...]:
        """Where a cube is, to a tenth of a millimetre: the key of cached query answers.

        A cube at rest still creeps by about a micrometre per tick; an exact key would
        never be asked twice.
        """
        return tuple(round(v, KEY_DIGITS) for v in self.sim.cube_position(cube))

    def remember(self, key: object, answer: object) -> None:
        """Keep a query's answer; forget them all now and then, so the memory stays small."""
        if len(self.queries) > QUERIES_KEPT:
            self.queries.clear()
        self.queries[key] = answer

    def path_blockers(self, traj: Trajectory, start: int = 0) -> set[str]:
        """Cubes on the floor on the rest of the path, and, except on a path to a pose,
        obstacles still in hand (or being let go of by a Place that has not ended)."""
        held = self.held
        found = {c for c in self.floor_cubes(traj.target, held)
                 if self.on_path(c, traj.path, start)}
        if traj.target not in self.poses:
            # An obstacle in hand is not yet put aside. But on the way to a pose (a spot
            # sampled to put an obstacle aside) it is being carried to where it goes: were
            # it to block that path too, nothing could ever put it down.
            found.update(c for c in (held, self.releasing)
                         if c is not None and c in traj.clearing)
        return found

    def blockers(self, traj: Trajectory) -> set[str]:
        """The cubes on the path, as `path_blockers` from its start.

        A trajectory with no path reports "(no path)" instead: never taken for a free one.
        """
        if not traj.path:
            return {"(no path)"}
        return self.path_blockers(traj)

    def close(self) -> None:
        """Disconnect the simulation; the state is unusable afterwards."""
        self.sim.close()
