"""The PyBullet world: geometric conditions and multi-tick skills behind the World protocol.

Conditions are evaluated from the scene every time they are ticked (robot near a
location, cube in hand, hand empty, cube on a region or pose, trajectory free), never
from a stored symbolic state, so changes made by external agents are seen at once.
Continuous parameters (trajectories, placement poses, the cube that blocks a path) are
supplied through `refine`, which the planner calls when it grounds an action template.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping

from btplan.bt.status import FAILURE, RUNNING, Status
from btplan.errors import WorldError
from btplan.model import ActionTemplate, Atom, GroundAction, Parameter, Task, instantiate
from btplan.worlds.pybullet import motion, samplers
from btplan.worlds.pybullet.agents import SceneAgents
from btplan.worlds.pybullet.geometry import clearance, distance
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.paths import CHECK_FROM, Trajectory
from btplan.worlds.pybullet.record import Recorder
from btplan.worlds.pybullet.scene import Point, Scene
from btplan.worlds.pybullet.sim import Sim
from btplan.worlds.pybullet.skills import ClearPath, MoveTo, Pick, Release, Skill

Key = tuple[str, tuple[str, ...]]
STEP = 0.05          # metres between waypoints of a path
PLAN_BUDGET = 1.0    # seconds OMPL may take for a path that avoids walls only
DETOUR_BUDGET = 0.1  # seconds for a path that also avoids the movable cubes


class PyBulletWorld:
    """A mobile robot with a gripper among walls and cubes; see the module docstring."""

    def __init__(self, task: Task, scene: Scene, seed: int = 0, gui: bool = False,
                 verbose: bool = False) -> None:
        motion.set_log_level(verbose)
        motion.seed_rng(seed + 1)  # OMPL refuses a zero seed
        self.task, self.scene = task, scene
        self.cube_names = tuple(sorted(c.name for c in scene.cubes))
        self.on_floor: dict[str, Point | None] = {c.name: c.at for c in scene.cubes}
        self.held: str | None = None
        self.clearing_now: str | None = None  # the cube a running ClearPath carries
        self.handled = 0  # cubes the robot grasped or put down so far
        self.base: Pose2 = scene.start
        self.trajectories: dict[str, Trajectory] = {}
        self.poses: dict[str, Point] = {}
        self.running: dict[Key, Skill] = {}
        # Logs of grounded actions, as every world keeps them (traces, --plan-out, agents).
        self.executed: list[GroundAction] = []
        self.started: list[GroundAction] = []
        self.halted: list[GroundAction] = []
        self.failed: list[GroundAction] = []
        self.agents: SceneAgents = SceneAgents()
        self.recorder: Recorder | None = None
        self.plan_seconds: list[float] = []
        self.action_ticks = 0
        self.current: str = ""
        self.on_frame: Callable[[PyBulletWorld], None] | None = None
        self._refined: dict[tuple[str, str, tuple[tuple[str, str], ...]], list[str]] = {}
        self._counter = itertools.count(1)
        self._no_detour: set[tuple[object, ...]] = set()
        self.waypoints_per_tick = max(1, round(scene.speed * scene.tick_seconds / STEP))
        self._check_objects()
        self.sim = Sim(scene, gui)  # after the checks: a refused scene leaves no connection open
        scene_names = {*self.cube_names, *(r.name for r in scene.regions)}
        # Initial facts about things the scene does not contain (a trajectory or pose the
        # problem declares) cannot be measured; they are kept as given.
        self.assumed = frozenset(a for a in task.initial_state
                                 if any(x not in scene_names for x in a.args))

    def _check_objects(self) -> None:
        known = set(self.cube_names) | {r.name for r in self.scene.regions}
        poses = set(self.task.objects_of(self._type_of("pose")))
        for name in self.task.objects_of(self._type_of("location")):
            if name not in known and name not in poses:
                raise WorldError(f"{name!r} is a location in the problem but not in the scene "
                                 f"{self.scene.path}; add it as a [[cube]] or [[region]]")

    def _type_of(self, wanted: str) -> str:
        return wanted if wanted in self.task.domain.type_parents else "object"

    # --- the scene, as the skills and agents see it ----------------------------------------

    @property
    def sim_seconds(self) -> float:
        return self.action_ticks * self.scene.tick_seconds

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
                if cube in traj.clearing and not self._on_path(cube, traj.path, 0):
                    traj.clearing.discard(cube)
        else:
            for traj in self.trajectories.values():
                traj.clearing.discard(cube)

    # --- conditions ----------------------------------------------------------------------

    def check(self, key: Key) -> bool:
        name, args = key
        if name == "near":
            return self.is_near(args[0])
        if name == "holding":
            return self.held == args[0] and self.held != self.clearing_now
        if name == "hand_empty":
            return self.held is None or self.held == self.clearing_now
        if name == "on":
            return self._on(args[0], args[1])
        if name == "free":
            return self._free(args[0])
        if name == "route":
            traj = self.trajectories.get(args[1])
            return traj is not None and traj.target == args[0]
        if name == "blocks":
            traj = self.trajectories.get(args[1])
            return traj is not None and args[0] in self.blockers(traj)
        raise WorldError(f"the PyBullet world cannot evaluate the condition {name!r}")

    def _on(self, cube: str, place: str) -> bool:
        at = self.on_floor.get(cube)
        if at is None:
            return False
        region = self.scene.region(place)
        if region is not None:
            return region.contains(*at)
        if place in self.poses:
            return distance(at, self.poses[place]) <= 0.1
        return False

    def _free(self, name: str) -> bool:
        traj = self.trajectories.get(name)
        if traj is None:
            return False
        self.prepare(name)
        return not self.blockers(traj)

    def facts(self) -> frozenset[Atom]:
        """Every condition of the domain's vocabulary that holds now, as atoms."""
        found: set[Atom] = set(self.assumed)
        locations = [*self.cube_names, *(r.name for r in self.scene.regions), *sorted(self.poses)]
        found.update(Atom("near", (n,)) for n in locations if self.is_near(n))
        found.add(Atom("hand_empty", ()) if self.check(("hand_empty", ())) else
                  Atom("holding", (str(self.held),)))
        found.update(Atom("on", (c, p)) for c in self.cube_names for p in locations
                     if self._on(c, p))
        for name in sorted(self.trajectories):
            traj = self.trajectories[name]
            found.add(Atom("route", (traj.target, name)))
            if traj.stale(self.base, traj.goal, self.layout()) or not self.present(traj.target):
                continue  # not measured without planning again; check(free(t)) does that
            if not self.blockers(traj):
                found.add(Atom("free", (name,)))
        return frozenset(found)

    # --- paths ---------------------------------------------------------------------------

    def approach(self, name: str, avoid_cubes: bool = True) -> Pose2 | None:
        return samplers.approach_pose(self, name, avoid_cubes)

    def prepare(self, name: str, slack: float = CHECK_FROM) -> None:
        """Plan the trajectory again if it was planned from elsewhere or its target moved.

        `slack` is how far from the path's start the robot may be: small when the robot is
        about to drive the path, larger when the path is only checked, which saves most
        re-planning while the robot drives elsewhere.
        """
        traj = self.trajectories[name]
        if traj.target in self.on_floor and not self.present(traj.target):
            return  # a cube taken out of the scene: keep the old path, nothing to reach
        goal = self.approach(traj.target) or self.approach(traj.target, avoid_cubes=False)
        if not traj.stale(self.base, goal, self.layout(), slack) or goal is None:
            return
        traj.path, traj.goal = self._plan(traj.target, goal), goal
        traj.layout = self.layout()
        traj.plans += 1

    def layout(self) -> tuple[object, ...]:
        """What the robot itself changed: a path planned before it moved a cube is stale.

        A cube moved by someone else is deliberately not part of it: the stored path is
        checked against it, so an obstacle that appears on the way blocks the path.
        """
        return (self.held, self.handled)

    def _plan(self, target: str, goal: Pose2) -> tuple[Pose2, ...]:
        start = self.base
        walls_only = self._solve(start, goal, [], PLAN_BUDGET)
        if walls_only is None:
            return ()
        path = walls_only
        if any(self._on_path(c, path, 0) for c in self.floor_cubes(target, self.held)):
            cubes = self.floor_cubes(target, self.held)
            layout = (target, tuple((c, self.on_floor[c]) for c in cubes),
                      round(start[0], 1), round(start[1], 1))
            if layout not in self._no_detour:
                detour = self._solve(start, goal, cubes, DETOUR_BUDGET)
                if detour is None:
                    self._no_detour.add(layout)
                else:
                    path = detour
        return path

    def _solve(self, start: Pose2, goal: Pose2, cubes: list[str], budget: float
               ) -> tuple[Pose2, ...] | None:
        def valid(x: float, y: float) -> bool:
            return self.sim.base_free(x, y, cubes)

        result = motion.plan_se2(start, goal, valid, self.scene.bounds, budget, STEP)
        if result is None:
            return None
        self.plan_seconds.append(result.seconds)
        return result.path

    def _on_path(self, cube: str, path: tuple[Pose2, ...], start: int) -> bool:
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
                 if self._on_path(c, traj.path, start)}
        if self.held is not None and self.held in traj.clearing:
            found.add(self.held)
        return found

    def blockers(self, traj: Trajectory) -> set[str]:
        if not traj.path:
            return {"(no path)"}
        return self.path_blockers(traj)

    # --- actions -------------------------------------------------------------------------

    def ground(self, key: Key) -> GroundAction:
        """The grounded action of a leaf key, for the logs."""
        template = self.task.domain.action_map.get(key[0])
        if template is None or len(template.parameters) != len(key[1]):
            raise WorldError(f"{key[0]}{key[1]} is not an action of domain {self.task.domain.name!r}")
        return instantiate(template, key[1])

    def start(self, key: Key) -> Status:
        self.started.append(self.ground(key))
        skill = self._skill(key)
        if skill is None:
            self.failed.append(self.ground(key))
            return FAILURE
        self.running[key] = skill
        return self.step(key)

    def step(self, key: Key) -> Status:
        skill = self.running.get(key)
        if skill is None:
            return FAILURE
        self.action_ticks += 1
        status = skill.step(self)
        self.current = f"{key[0]}({', '.join(key[1])})"
        if isinstance(skill, ClearPath):
            self.current += f": {skill.doing} {skill.cube}"
        if status is not RUNNING:
            del self.running[key]
            log = self.failed if status is FAILURE else self.executed
            log.append(self.ground(key))
        if self.on_frame is not None:
            self.on_frame(self)
        return status

    def halt(self, key: Key) -> None:
        skill = self.running.pop(key, None)
        if skill is not None:
            self.halted.append(self.ground(key))
            skill.halt()

    def _skill(self, key: Key) -> Skill | None:
        name, args = key
        if name == "MoveTo" and len(args) == 2 and args[1] in self.trajectories:
            return MoveTo(self, args[0], args[1])
        if name == "Pick" and len(args) == 1:
            return Pick(self, args[0])
        if name == "Place" and len(args) == 2:
            spot = samplers.place_spot(self, args[1]) if self.is_near(args[1]) else None
            return Release(self, args[0], spot)
        if name == "ClearPath" and len(args) == 3 and args[1] in self.poses:
            if self.held is not None or not self.is_near(args[0]):
                return None
            return ClearPath(self, args[0], args[1])
        if name == "Drop" and len(args) == 1:
            return Release(self, args[0], samplers.drop_spot(self), ticks=1)
        if name in ("MoveTo", "Pick", "Place", "ClearPath", "Drop"):
            return None
        raise WorldError(f"the PyBullet world has no skill for the action {name!r}")

    # --- refinement ----------------------------------------------------------------------

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """Values for a continuous parameter; the same question always gets the same answer."""
        memo = (template.name, parameter.name, tuple(sorted(binding.items())))
        if memo not in self._refined:
            self._refined[memo] = samplers.refine_values(self, template, binding, parameter)
        return list(self._refined[memo])

    def new_trajectory(self, target: str) -> str:
        name = f"traj{next(self._counter)}"
        self.trajectories[name] = Trajectory(name, target)
        self.prepare(name)
        return name

    def sample_pose(self, avoid: Trajectory | None) -> str | None:
        """Reserve a spot off `avoid`'s path to put an obstacle, and name it."""
        spot = samplers.aside_spot(self, avoid)
        if spot is None:
            return None
        name = f"pose{len(self.poses) + 1}"
        self.poses[name] = spot
        return name

    # --- lifecycle -----------------------------------------------------------------------

    def stats(self) -> dict[str, float]:
        """Simulated time and OMPL effort so far, for the run's closing note."""
        moves = sum(1 for a in self.started if a.name in ("MoveTo", "ClearPath"))
        total = sum(self.plan_seconds)
        return {
            "sim_seconds": round(self.sim_seconds, 3),
            "action_ticks": self.action_ticks,
            "ompl_solves": len(self.plan_seconds),
            "ompl_seconds_total": round(total, 4),
            "ompl_ms_per_solve": round(1000 * total / max(1, len(self.plan_seconds)), 2),
            "ompl_ms_max": round(1000 * max(self.plan_seconds, default=0.0), 2),
            "moves_started": moves,
            "ompl_ms_per_move": round(1000 * total / max(1, moves), 2),
        }

    def scene_agents(self) -> list[SceneAgents]:
        """The scene's scripted external events, as one agent acting before each tick."""
        return [self.agents]

    def close(self) -> None:
        """Save the recording (if any) and disconnect from PyBullet."""
        self.running.clear()
        if self.recorder is not None:
            self.recorder.save()
        self.sim.close()
        motion.release()

