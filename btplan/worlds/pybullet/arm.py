"""Arm and base motions written as generators that yield once per physics substep.

A skill strings them together (reach, descend, close, lift); the runner in skills.py
steps the physics after every yield and ends the tick after `substeps` of them, so a
motion takes as many ticks as its simulated duration needs. Joint moves go straight in
joint space when that is collision-free, and through an OMPL plan when it is not.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Generator, Sequence

from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.robot import CARRY, LOWER, OPEN, SHUT, UPPER
from btplan.worlds.pybullet.sim import HZ
from btplan.worlds.pybullet.state import SceneState

Motion = Generator[None, None, bool]
"""Yields once per substep; returns whether it got where it was going."""
Q = tuple[float, ...]

JOINT_SPEED = 2.0      # rad/s, the fastest joint
TURN_SPEED = 2.0       # rad/s of the base turning on the spot
CHECK_STEP = 0.08      # rad between collision checks along a joint move
SETTLE = 0.25          # s the arm may take to settle on its last target
ARM_ITERATIONS = 200   # RRTConnect iterations for an arm motion (~4 ms each)
AT = 0.02              # rad: close enough to a joint target
LOW = 0.2              # m: a hand lower than this is lifted before the base moves
DRAW_IN = 0.08         # m a held cube is drawn in towards the base as it is lifted
HELD_IN = 0.04         # m inside `near` a held cube stays on a planned detour
LEAVE = 0.15           # rad around the start of a detour where it may be farther out


class Timings:
    """Wall time spent in IK and in arm planning (OMPL and collision checks), for bench/."""

    def __init__(self) -> None:
        self.ik = 0.0
        self.arm_planning = 0.0
        self.ompl_solves = 0
        self.ompl = 0.0
        self.ompl_followed = 0
        """Arm motions that went along an OMPL joint-space path (not just checked by one)."""


def obstacles(state: SceneState, *ignored: str | None) -> list[int]:
    """Bodies the arm must not touch: walls and cubes other than `ignored`."""
    sim = state.sim
    return sim.walls + [sim.cubes[c] for c in state.cube_names
                        if c not in ignored and state.present(c)]


def solve(state: SceneState, timings: Timings, target: Sequence[float], yaw: float) -> Q | None:
    """IK for the finger tip at `target` (metres, world frame), hand down, turned by `yaw`.

    None when it is out of reach; the wall time goes to `timings.ik`.
    """
    began = time.perf_counter()
    try:
        return state.sim.robot.solve_ik(target, yaw)
    finally:
        timings.ik += time.perf_counter() - began


def plan_arm(state: SceneState, timings: Timings, goal: Q, *ignored: str | None
             ) -> list[Q] | None:
    """A collision-free joint path to `goal`: straight if it is free, else OMPL's."""
    began = time.perf_counter()
    robot, floor = state.sim.robot, state.sim.floor
    bodies = obstacles(state, *ignored)

    # On a planned detour, a held cube stays within `near` of the base (or no farther than
    # the motion's ends): what the robot holds stays near it, and the conditions do not
    # flicker while the arm moves round things.
    x, y, _ = state.base

    def tip_distance(q: Q) -> float:
        robot.set_arm(q)
        tx, ty, _ = robot.tip()
        return math.hypot(tx - x, ty - y)

    saved = robot.arm_state()
    start = saved[0]
    reach: float | None = None
    reach_start = 0.0

    def touches(q: Q) -> bool:
        return robot.arm_touches(q, bodies, floor, restore=False)

    def free(q: Q) -> bool:
        if touches(q):
            return False
        if reach is None:
            return True
        tx, ty, _ = robot.tip()
        out = math.hypot(tx - x, ty - y)
        # Farther out than that only close to the start, where the cube already is.
        return out <= reach or (out <= reach_start and distance(q, start) < LEAVE)

    try:
        if touches(goal):
            return None
        if straight_free(start, goal, lambda q: not touches(q)):
            return [start, goal]
        if state.held is not None:  # only a planned detour could swing the cube away
            reach = max(state.scene.near - HELD_IN, tip_distance(goal))
            reach_start = tip_distance(start)
        timings.ompl_solves += 1
        solving = time.perf_counter()
        plan = motion.plan_joints(start, goal, free, LOWER, UPPER, ARM_ITERATIONS)
        timings.ompl += time.perf_counter() - solving
        return None if plan is None else list(plan.path)
    finally:
        robot.restore(saved)
        timings.arm_planning += time.perf_counter() - began


def distance(a: Q, b: Q) -> float:
    """The largest joint difference: what a joint move takes time for."""
    return max(abs(u - v) for u, v in zip(a, b))


def straight_free(start: Q, goal: Q, free: Callable[[Q], bool]) -> bool:
    """Whether the straight joint-space move from `start` to `goal` stays free.

    `free` is asked every CHECK_STEP radians of the largest joint's change; both ends are
    left out (the arm is at the start, and callers check the goal themselves).
    """
    steps = max(1, math.ceil(max(abs(a - b) for a, b in zip(start, goal)) / CHECK_STEP))
    return all(free(tuple(a + (b - a) * k / steps for a, b in zip(start, goal)))
               for k in range(1, steps))


def follow(state: SceneState, path: Sequence[Q]) -> Motion:
    """Command the arm along `path` at JOINT_SPEED, then let it settle on the last point."""
    robot = state.sim.robot
    per_step = JOINT_SPEED / HZ
    for a, b in zip(path, path[1:]):
        n = max(1, math.ceil(max(abs(x - y) for x, y in zip(a, b)) / per_step))
        for k in range(1, n + 1):
            robot.command(tuple(x + (y - x) * k / n for x, y in zip(a, b)))
            yield
    goal = path[-1]
    for _ in range(int(SETTLE * HZ)):
        if max(abs(x - y) for x, y in zip(robot.joints(), goal)) < AT:
            return True
        yield
    return max(abs(x - y) for x, y in zip(robot.joints(), goal)) < 3 * AT


def move_arm(state: SceneState, timings: Timings, goal: Q, *ignored: str | None) -> Motion:
    """Plan (straight or OMPL) and follow; False when no collision-free motion exists."""
    solves = timings.ompl_solves
    path = plan_arm(state, timings, goal, *ignored)
    if path is None:
        return False
    timings.ompl_followed += timings.ompl_solves > solves
    return (yield from follow(state, path))


def clear_of_floor(state: SceneState, timings: Timings) -> Motion:
    """Raise a low hand before the base turns or drives: up, and a little in towards the
    base when it holds a cube, so that the cube is well within `near` from then on."""
    robot = state.sim.robot
    x, y, z = robot.tip()
    if z >= LOW:
        return True
    bx, by, _ = state.base
    out = math.hypot(x - bx, y - by)
    pull = min(DRAW_IN, max(0.0, out - 0.45)) / out if state.held is not None and out else 0.0
    up = solve(state, timings, (x - (x - bx) * pull, y - (y - by) * pull, z + 0.15),
               robot.tip_yaw())
    if up is None:
        up = solve(state, timings, (x, y, z + 0.15), robot.tip_yaw())
    if up is None:
        return False
    return (yield from follow(state, [robot.joints(), up]))


def to_carry(state: SceneState, timings: Timings, *ignored: str | None) -> Motion:
    """Fold the arm over the base; lift the hand first when it is low (near the floor)."""
    robot = state.sim.robot
    if max(abs(x - y) for x, y in zip(robot.joints(), CARRY)) < AT:
        return True
    yield from clear_of_floor(state, timings)
    if (yield from move_arm(state, timings, CARRY, *ignored)):
        return True
    return (yield from follow(state, [robot.joints(), CARRY]))  # last resort: straight


def fingers(state: SceneState, width: float, body: int | None = None) -> Motion:
    """Open or close the fingers; closing stops once both touch `body` (and grips it)."""
    robot = state.sim.robot
    robot.fingers(width)
    last = robot.finger_width()
    for k in range(int(0.5 * HZ)):
        yield
        now = robot.finger_width()
        if body is not None and width == SHUT and robot.attach(body):
            return True
        if abs(now - 2 * width) < 0.002 or (k > 12 and abs(now - last) < 1e-5):
            break
        last = now
    return body is None or (width == SHUT and robot.attach(body))


def turn_to(state: SceneState, yaw: float) -> Motion:
    """Turn the base on the spot to `yaw`."""
    x, y, now = state.base
    per_step = TURN_SPEED / HZ
    while True:
        error = math.remainder(yaw - now, math.tau)
        if abs(error) <= per_step:
            state.move_base((x, y, yaw))
            return True
        now += math.copysign(per_step, error)
        state.move_base((x, y, now))
        yield


def drive(state: SceneState, goal: Pose2, speed: float) -> Motion:
    """Drive the base in a straight line to `goal`'s position (turning to face it first)."""
    x, y, yaw = state.base
    gx, gy, _ = goal
    length = math.hypot(gx - x, gy - y)
    if length > 1e-4:
        heading = math.atan2(gy - y, gx - x)
        if abs(math.remainder(heading - yaw, math.tau)) > 0.05:
            yield from turn_to(state, heading)
        per_step = speed / HZ
        n = max(1, math.ceil(length / per_step))
        for k in range(1, n + 1):
            state.move_base((x + (gx - x) * k / n, y + (gy - y) * k / n, heading))
            if k < n:
                yield
    return True


def opened(state: SceneState) -> Motion:
    """Let go of any grasp and open the fingers, for at most half a second; always True."""
    state.sim.robot.open()
    return (yield from fingers(state, OPEN))


def pause(seconds: float) -> Motion:
    """Let the physics run (a released cube settles)."""
    for _ in range(int(seconds * HZ)):
        yield
    return True
