"""The robot's skills: MoveTo, Pick, Place, PlaceAside and Drop, each running over ticks.

A skill is created when the tree starts an action and stepped on each later tick that
reaches it; it answers RUNNING until it is done. Halting simply drops the skill, which
leaves the robot standing where it is (the base is moved kinematically). Durations are
in ticks so that runs are reproducible; MoveTo covers `speed * tick_seconds` metres of
its path per tick.
"""

from __future__ import annotations

from typing import Protocol

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.worlds.pybullet.geometry import facing
from btplan.worlds.pybullet.paths import DRIVE_FROM
from btplan.worlds.pybullet.routes import STEP, Routes
from btplan.worlds.pybullet.state import SceneState

GRASP_TICKS = 3
RELEASE_TICKS = 2
MAX_RETARGETS = 3


class Skill(Protocol):
    def step(self) -> Status: ...

    def halt(self) -> None: ...


class MoveTo:
    """Follows the named trajectory; fails when its remaining path is no longer free."""

    def __init__(self, routes: Routes, target: str, trajectory: str) -> None:
        self.routes, self.world = routes, routes.state
        self.target, self.name = target, trajectory
        self.index = 0
        self.retargets = 0
        scene = routes.state.scene
        self.waypoints_per_tick = max(1, round(scene.speed * scene.tick_seconds / STEP))
        routes.prepare(trajectory, DRIVE_FROM)
        self.traj = routes.state.trajectories[trajectory]
        self.traj.executing = True

    def step(self) -> Status:
        world = self.world
        path = self.traj.path
        if not path or world.path_blockers(self.traj, self.index):
            return self.stop(FAILURE)
        self.index = min(self.index + self.waypoints_per_tick, len(path) - 1)
        world.move_base(path[self.index])
        if world.is_near(self.target):
            # Within reach is what the postcondition asks; the tree would stop us here anyway.
            return self.stop(SUCCESS)
        if self.index < len(path) - 1:
            return RUNNING
        # The target moved while we drove: plan again from here, a few times at most.
        self.retargets += 1
        if self.retargets > MAX_RETARGETS:
            return self.stop(FAILURE)
        self.traj.executing = False
        self.routes.prepare(self.name, DRIVE_FROM)
        self.traj.executing = True
        self.index = 0
        return RUNNING

    def stop(self, status: Status) -> Status:
        self.traj.executing = False
        return status

    def halt(self) -> None:
        self.traj.executing = False


class Pick:
    """Turns to the cube, closes the gripper, lifts: the cube is attached on the last tick."""

    def __init__(self, world: SceneState, cube: str) -> None:
        self.world, self.cube = world, cube
        self.ticks = 0
        self.ok = world.held is None and world.present(cube) and world.is_near(cube)
        if self.ok:
            world.move_base(facing(world.base[:2], world.location(cube)))

    def step(self) -> Status:
        world = self.world
        if not self.ok or not world.present(self.cube) or not world.is_near(self.cube):
            return FAILURE
        self.ticks += 1
        if self.ticks < GRASP_TICKS:
            return RUNNING
        world.grasp(self.cube)
        return SUCCESS

    def halt(self) -> None:
        pass


class Release:
    """Puts the held cube down at a spot chosen when the action starts (Place, Drop)."""

    def __init__(self, world: SceneState, cube: str, spot: tuple[float, float] | None,
                 ticks: int = RELEASE_TICKS) -> None:
        self.world = world
        self.cube, self.spot, self.duration = cube, spot, ticks
        self.ticks = 0
        self.ok = world.held == cube and spot is not None
        if self.ok and spot is not None:
            world.move_base(facing(world.base[:2], spot))

    def step(self) -> Status:
        world = self.world
        if not self.ok or world.held != self.cube or self.spot is None:
            return FAILURE
        self.ticks += 1
        if self.ticks < self.duration:
            return RUNNING
        world.release(self.spot)
        return SUCCESS

    def halt(self) -> None:
        pass


class ClearPath:
    """Pick an obstacle, carry it to a pose off the path, put it down: one symbolic action.

    Its effect (the path is free) only counts at the end, as for every action of the
    domain, so while it runs the world hides its intermediate state from the
    conditions: the cube being carried leaves the hand "empty" for the task, and the
    robot stays "near" it. Halting it mid-way leaves the cube in the gripper.
    """

    def __init__(self, routes: Routes, cube: str, pose: str) -> None:
        self.routes, self.world = routes, routes.state
        self.cube, self.pose = cube, pose
        self.phase: Skill = Pick(self.world, cube)
        self.stage = 0
        self.world.clearing_now = cube

    @property
    def doing(self) -> str:
        """What the robot is doing within the action, for the recorded frames."""
        return ("picking", "carrying", "putting down")[self.stage]

    def step(self) -> Status:
        status = self.phase.step()
        if status is RUNNING:
            return RUNNING
        if status is FAILURE or self.stage == 2:
            return self.stop(status)
        self.stage += 1
        if self.stage == 1:
            self.phase = MoveTo(self.routes, self.pose, self.routes.new_trajectory(self.pose))
        else:
            self.phase = Release(self.world, self.cube, self.world.poses[self.pose])
        return RUNNING

    def stop(self, status: Status) -> Status:
        self.world.clearing_now = None
        return status

    def halt(self) -> None:
        self.phase.halt()
