"""The robot's skills: MoveTo, Pick, Place and Drop, each running over ticks.

A skill is a script (a generator of arm and base motions from arm.py) that the runner
steps: on every tick it runs `substeps` physics steps (240 Hz), and the skill answers
RUNNING until its script returns SUCCESS or FAILURE. Success is read from the scene
(the cube is between the closed fingers, or has come to rest where it was put), never
assumed. A halted skill leaves the world consistent: a cube held stays held, a grasp
not yet made is let go, and the arm folds back over the base.
"""

from __future__ import annotations

import math
from collections.abc import Generator
from typing import Protocol

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.worlds.pybullet import arm, samplers
from btplan.worlds.pybullet.arm import Timings
from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.paths import DRIVE_FROM
from btplan.worlds.pybullet.robot import SHUT
from btplan.worlds.pybullet.routes import Routes
from btplan.worlds.pybullet.scene import Point
from btplan.worlds.pybullet.sim import HZ
from btplan.worlds.pybullet.state import SceneState

Script = Generator[None, None, Status]
ABOVE = 0.12          # metres above the grasp or put-down point where the hand approaches
MAX_RETARGETS = 3
SAFE_SECONDS = 3.0    # the longest a halted skill may take to fold the arm


class Skill(Protocol):
    """What runs an action leaf: stepped once per tick until it stops answering RUNNING."""

    reason: str
    """Why the skill failed, when it knows ('' otherwise): read once it returned FAILURE."""

    def step(self) -> Status:
        """Run one tick of the skill: RUNNING, or its outcome, repeated if it is stepped again."""
        ...

    def halt(self) -> None:
        """Stop the skill before it ends, leaving the robot safe and the world consistent."""
        ...


class Scripted:
    """Runs a script for one tick's worth of physics substeps per `step`."""

    def __init__(self, state: SceneState, timings: Timings, script: Script) -> None:
        self.state, self.timings, self.script = state, timings, script
        self.substeps = max(1, round(state.scene.tick_seconds * HZ))
        self.done: Status | None = None
        self.started = False
        self.reason = ""

    def step(self) -> Status:
        """Run `substeps` physics steps, the script looking at the scene after each.

        Once the script returns, its outcome (and a failure's reason, from the state) is kept
        and answered on every later step.
        """
        if self.done is not None:
            return self.done
        sim = self.state.sim
        # The script sets its commands, the physics steps, and the script looks at the
        # result: after the tick's last step too, so a postcondition reached on that
        # step ends the action in this tick, before the tree sees it and halts it.
        try:
            if not self.started:
                self.started = True
                next(self.script)
            for _ in range(self.substeps):
                sim.step()
                next(self.script)
        except StopIteration as finished:
            self.done = finished.value
            if self.done is FAILURE:
                self.reason = self.state.failure
            self.state.failure = ""
            return finished.value  # type: ignore[no-any-return]
        return RUNNING

    def halt(self) -> None:
        """Stop the script, then make the robot safe (synchronously, bounded in time)."""
        self.script.close()
        if self.done is None:
            settle(self.state, self.timings)


def refuse(state: SceneState, reason: str) -> Status:
    """FAILURE, with the reason the skill gives for it (Scripted.reason)."""
    state.failure = reason
    return FAILURE


def settle(state: SceneState, timings: Timings) -> None:
    """Keep a cube that is firmly held, let go of anything else, fold the arm."""
    robot = state.sim.robot
    held = state.held
    if held is None:
        robot.open()
    elif robot.grip is None:
        robot.attach(state.sim.cubes[held])
    safe = arm.to_carry(state, timings, held)
    for _ in range(int(SAFE_SECONDS * HZ)):
        try:
            next(safe)
        except StopIteration:
            break
        state.sim.step()


def facing(state: SceneState, at: Point) -> float:
    """The yaw (radians) that turns the base, where it stands, towards `at`."""
    x, y, _ = state.base
    return math.atan2(at[1] - y, at[0] - x)


def grasp_yaws(state: SceneState, cube: str) -> list[float]:
    """The hand's yaw for each side of the cube, the one turning the wrist least first."""
    yaw = state.sim.cube_yaw(cube)
    hand = state.base[2]
    return sorted((yaw + k * math.pi / 2 for k in range(4)),
                  key=lambda a: (round(abs(math.remainder(a - hand, math.tau)), 4), a))


def pick(state: SceneState, timings: Timings, cube: str) -> Script:
    """Face the cube, reach above it, descend, close, lift; SUCCESS once it is in hand."""
    if state.in_hand() is not None or not state.present(cube) or not state.is_near(cube):
        return FAILURE
    if state.held is not None:
        # The fingers closed on a cube that no arm lifted (a pick halted as it lifted):
        # `hand_empty` holds, so the tree picks again; let go first, or every pick from
        # here would fail at once.
        yield from arm.opened(state)
    robot, body = state.sim.robot, state.sim.cubes[cube]
    yield from arm.clear_of_floor(state, timings)
    yield from arm.turn_to(state, facing(state, state.location(cube)))
    x, y, z = state.sim.cube_position(cube)
    reach: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    for yaw in grasp_yaws(state, cube):  # a sampled grasp and its approach, both collision-free
        above = arm.solve(state, timings, (x, y, z + ABOVE), yaw)
        at = arm.solve(state, timings, (x, y, z), yaw) if above is not None else None
        if above is not None and at is not None and arm.plan_arm(state, timings, at, cube):
            reach = (above, at)
            break
    if reach is None:
        # Out of reach from here, or every grasp collides: not near after all, so that
        # the tree drives up to it (MoveTo ends at a pose facing it).
        state.missed_reach(cube)
        return FAILURE
    state.out_of_reach.pop(cube, None)
    yield from arm.opened(state)
    if not (yield from arm.move_arm(state, timings, reach[0], cube)):
        return (yield from give_up(state, timings))
    if moved(state, cube, (x, y, z)):
        return (yield from give_up(state, timings))  # someone took it while we reached
    yield from arm.follow(state, [robot.joints(), reach[1]])
    if not (yield from arm.fingers(state, SHUT, body)):
        return (yield from give_up(state, timings))  # missed: the fingers closed on nothing
    state.handled += 1
    # Lift. Done as soon as the cube is held off the floor: that is `holding(c)`, and a
    # reactive tree would halt the action on the next tick anyway. MoveTo folds the arm.
    for _ in arm.follow(state, [robot.joints(), reach[0]]):
        if state.lifted(cube):
            return SUCCESS
        yield
    return SUCCESS if state.lifted(cube) else (yield from give_up(state, timings))


def moved(state: SceneState, cube: str, at: tuple[float, float, float]) -> bool:
    """Whether `cube` left the scene or is over 1.5 cm from `at` (taken while the arm reached)."""
    return not state.present(cube) or math.dist(state.sim.cube_position(cube), at) > 0.015


def give_up(state: SceneState, timings: Timings) -> Script:
    """Open the hand, fold the arm, and report FAILURE."""
    yield from arm.opened(state)
    yield from arm.to_carry(state, timings)
    return FAILURE


def put_down(state: SceneState, timings: Timings, cube: str, spot: Point | None,
             place: str | None) -> Script:
    """Face the spot, lower the cube onto it, open, let it settle; check where it rests."""
    if spot is None or state.held != cube:
        return FAILURE
    robot = state.sim.robot
    yield from arm.clear_of_floor(state, timings)
    yield from arm.turn_to(state, facing(state, spot))
    z = state.scene.cube_size / 2 + 0.01
    yaw = robot.tip_yaw()
    above = arm.solve(state, timings, (spot[0], spot[1], z + ABOVE), yaw)
    at = arm.solve(state, timings, (spot[0], spot[1], z), yaw) if above is not None else None
    if above is None or at is None or not (yield from arm.move_arm(state, timings, above, cube)):
        if place is None:
            state.missed_drop(spot)  # out of reach, or no free way there: Drop tries elsewhere
        return FAILURE  # the cube stays in hand
    yield from arm.follow(state, [robot.joints(), at])

    def done() -> bool:
        # Place achieves on(c, l); Drop achieves an empty hand: done as soon as the cube
        # has left the hand.
        if place is not None:
            return state.on(cube, place)
        return state.held != cube

    # Open, lift the hand clear, wait for the cube to settle: done as soon as the cube
    # rests where it was put (the postcondition), as for Pick. The next skill folds the arm.
    # Until then the cube still blocks the paths it blocked: only a Place that has ended
    # has put it aside, and the tree must not halt this one as the hand opens.
    state.releasing = cube
    try:
        for motion in (arm.opened(state), arm.follow(state, [robot.joints(), above]),
                       arm.pause(0.5)):
            for _ in motion:
                if done():
                    state.released(cube)
                    return SUCCESS
                yield
    finally:
        state.releasing = None
    state.released(cube)
    yield from arm.to_carry(state, timings)
    return FAILURE


def move_to(routes: Routes, timings: Timings, target: str, trajectory: str) -> Script:
    """Fold the arm, then follow the trajectory; FAILURE when the way ahead gets blocked.

    The path is driven only from where it starts, the robot's pose: a path that could not
    be planned again from here (no pose next to the target is free, or no way leads
    there) fails the move at once, with the reason, instead of driving the old path from
    wherever it began. Each of the few re-plans after a target that moved starts from
    the robot too, so a move that makes no progress ends within a bounded time.
    """
    state = routes.state
    yield from arm.to_carry(state, timings, state.held)
    traj = state.trajectories[trajectory]
    speed = state.scene.speed
    substeps = max(1, round(state.scene.tick_seconds * HZ))
    retargets = 0
    try:
        why = drive_from_here(routes, trajectory)
        if why:
            return refuse(state, why)
        index = 0
        while True:
            path = traj.path
            if not path:
                return refuse(state, f"no path from here to {target}")
            blockers = state.path_blockers(traj, index)
            if blockers:
                return refuse(state, f"the way to {target} is blocked by "
                                     f"{', '.join(sorted(blockers))}")
            # One tick's worth of path, checked at the start of the tick as before.
            budget = substeps
            while budget > 0 and index < len(path) - 1:
                index += 1
                for _ in arm.drive(state, path[index], speed):
                    if state.is_near(target):
                        return SUCCESS  # within reach: the postcondition holds
                    budget -= 1
                    yield
            if index >= len(path) - 1:
                state.out_of_reach.pop(target, None)  # at the approach pose now
            if state.is_near(target):
                return SUCCESS
            if index >= len(path) - 1:
                retargets += 1  # the target moved while we drove: plan again from here
                if retargets > MAX_RETARGETS:
                    return refuse(state, f"{target} moved away each of the {MAX_RETARGETS} "
                                         "times the robot got to it")
                why = drive_from_here(routes, trajectory)
                if why:
                    return refuse(state, why)
                index = 0
            if budget > 0:
                for _ in range(budget):
                    yield
    finally:
        traj.executing = False


def drive_from_here(routes: Routes, trajectory: str) -> str:
    """Plan the trajectory again from the robot if needed, and mark it driven; why it
    cannot be driven from here ('' when it can)."""
    state = routes.state
    traj = state.trajectories[trajectory]
    traj.executing = False
    routes.prepare(trajectory, DRIVE_FROM)
    traj.executing = True
    target = traj.target
    if target in state.sim.cubes and not state.present(target):
        return f"{target} is not in the scene"
    if samplers.approach_pose(state, target, avoid_cubes=False) is None:
        # The path kept leads to where the target was: driving it would be no progress.
        if state.missed_poses(target):
            return f"every free pose next to {target} was tried"
        return f"no free pose next to {target} to drive to"
    if traj.path and distance(traj.path[0], state.base) <= DRIVE_FROM:
        return ""
    return f"no path from here to {target}"
