"""SE(2) motion planning for the mobile base with OMPL (RRTConnect + path simplification).

OMPL is imported only when a plan is asked for, so that loading btplan costs nothing on
a machine without the simulation extra. Collision checking is delegated to a callable
(the PyBullet scene), which keeps this module free of any simulator detail.
"""

from __future__ import annotations

import gc
import importlib
import itertools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

Pose2 = tuple[float, float, float]
"""x, y (metres) and yaw (radians) of the base in the plane."""


@dataclass(frozen=True, slots=True)
class PlanResult:
    """A solved path with the time OMPL took, kept for the run's statistics."""

    path: tuple[Pose2, ...]
    seconds: float


def _ompl(part: str) -> Any:
    """An OMPL submodule, imported on first use (OMPL ships no type information)."""
    return importlib.import_module(f"ompl.{part}")


def set_log_level(verbose: bool) -> None:
    """OMPL prints an Info line per solve; only show them when the user asked for it."""
    ou = _ompl("util")
    ou.setLogLevel(ou.LogLevel.LOG_INFO if verbose else ou.LogLevel.LOG_NONE)


def release() -> None:
    """Collect OMPL objects no longer referenced, before the interpreter exits."""
    gc.collect()


def seed_rng(seed: int) -> None:
    """Seed OMPL for one run, so that the run's motion plans depend on its seed alone.

    OMPL draws the seed of every generator it creates (each sampler, nearest-neighbour
    structure and path simplifier of each solve) from one process-wide stream. Seeding
    that stream again when a world opens makes a run's plans independent of the runs
    this process did before, so a sweep's rows do not depend on which worker ran which
    seed, or in what order. OMPL reseeds the stream even after generators were made
    (tests/worlds/pybullet/test_motion.py holds it to that), but it logs an error saying
    it cannot tell whether earlier generators are still in use: none are, since every
    solve below makes its own, so the message is silenced for the call.
    """
    ou = _ompl("util")
    level = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    try:
        ou.RNG.setSeed(seed + 1)  # OMPL takes 0 for "no seed"
    finally:
        ou.setLogLevel(level)


class Work:
    """A planner's termination condition that counts its checks instead of the clock.

    RRTConnect checks the condition once per iteration (one sample, one extension and
    one connection attempt), and the path simplifier once per round of shortcuts, so a
    limit on checks is a limit on work: the same question gets the same answer however
    loaded the machine is, where a time budget gave different paths, and sometimes
    none, from one run of a seed to the next.
    """

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.used = 0

    def __call__(self) -> bool:
        self.used += 1
        return self.used > self.limit

    def condition(self) -> Any:
        """This counter as the PlannerTerminationCondition that OMPL's solve and simplify take."""
        return _ompl("base").PlannerTerminationCondition(self)


def ompl_yaw(yaw: float) -> float:
    """`yaw` in [-pi, pi): OMPL's SE2 space takes a state at exactly +pi (a robot facing
    due west, as `atan2` gives it) for out of bounds, and the solve fails with no word."""
    wrapped = math.remainder(yaw, math.tau)
    return wrapped - math.tau if wrapped >= math.pi else wrapped


def plan_se2(
    start: Pose2,
    goal: Pose2,
    valid: Callable[[float, float], bool],
    bounds: tuple[float, float, float, float],
    iterations: int = 2000,
    step: float = 0.05,
) -> PlanResult | None:
    """Plan from `start` to `goal` with RRTConnect, simplify, interpolate every `step` metres.

    `valid(x, y)` says whether the robot's footprint fits at (x, y); the footprint is a disc,
    so the yaw does not change validity and the heading along the path is computed after.
    Returns None when no path is found within `iterations` of RRTConnect's.
    """
    ob, og = _ompl("base"), _ompl("geometric")

    space = ob.SE2StateSpace()
    box = ob.RealVectorBounds(2)
    box.setLow(0, bounds[0])
    box.setHigh(0, bounds[1])
    box.setLow(1, bounds[2])
    box.setHigh(1, bounds[3])
    space.setBounds(box)
    setup = og.SimpleSetup(space)

    def checker(state: Any) -> bool:
        return valid(state.getX(), state.getY())

    setup.setStateValidityChecker(checker)
    info = setup.getSpaceInformation()
    info.setStateValidityCheckingResolution(0.01)  # of the space extent: ~7 cm for the scene
    s, g = space.allocState(), space.allocState()
    for state, pose in ((s, start), (g, goal)):
        state.setX(pose[0])
        state.setY(pose[1])
        state.setYaw(ompl_yaw(pose[2]))
    setup.setStartAndGoalStates(s, g)
    setup.setPlanner(og.RRTConnect(info))
    began, work = time.perf_counter(), Work(iterations)
    try:
        solved = bool(setup.solve(work.condition())) and setup.haveExactSolutionPath()
        if not solved:
            return None
        setup.simplifySolution(Work(SIMPLIFY_ROUNDS).condition())
        raw = setup.getSolutionPath()
        points = [(raw.getState(i).getX(), raw.getState(i).getY()) for i in range(raw.getStateCount())]
        return PlanResult(densify(points, start, goal, step), time.perf_counter() - began)
    finally:
        # Drop OMPL objects (and the Python checker they hold) now; `release` collects
        # them, or nanobind reports leaked instances at interpreter exit.
        setup.clear()
        del setup, info, checker, s, g, space


def escape(start: Pose2, valid: Callable[[float, float], bool], reach: float,
           step: float = 0.01, directions: int = 16) -> Pose2 | None:
    """The valid state nearest `start` within `reach`, for a start the checker rejects.

    The robot's footprint is a conservative disc: a base halted on a path that grazed a
    wall between two of OMPL's checks, or beside a cube pushed against it, stands where
    the disc touches something though nothing collides. A planner that rejects such a
    start finds no path from there to anywhere, and the robot is stuck for good. As
    motion planners do with a start in collision, the measured start is accepted and the
    path leaves it in a straight line to the nearest valid state: rings of growing
    radius, `step` metres apart, so the line's points every `step` before it were
    rejected too (it moves out of the grazing, never through an obstacle, for a `reach`
    well under the footprint's radius). None when nothing within `reach` is valid.
    """
    for k in range(1, math.floor(reach / step + 1e-9) + 1):
        r = k * step
        for j in range(directions):
            a = start[2] + math.tau * j / directions
            x, y = start[0] + r * math.cos(a), start[1] + r * math.sin(a)
            if valid(x, y):
                return (x, y, start[2])
    return None


def densify(
    points: list[tuple[float, float]], start: Pose2, goal: Pose2, step: float
) -> tuple[Pose2, ...]:
    """Waypoints every `step` metres along the polyline, facing the direction of travel.

    The first pose keeps the start heading and the last one the goal heading, so the base
    turns on the spot at both ends as a differential-drive robot would.
    """
    out: list[Pose2] = [start]
    for (x0, y0), (x1, y1) in itertools.pairwise(points):
        length = math.hypot(x1 - x0, y1 - y0)
        if length < 1e-9:
            continue
        yaw = math.atan2(y1 - y0, x1 - x0)
        n = max(1, math.ceil(length / step))
        out.extend((x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n, yaw) for k in range(1, n + 1))
    out.append(goal)
    return tuple(out)


def path_length(path: tuple[Pose2, ...]) -> float:
    """The length of the path in the plane, in metres (yaw ignored); 0 for fewer than two poses."""
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in itertools.pairwise(path))


SIMPLIFY_ROUNDS = 1000
"""The most checks of its termination condition a path's simplification may make."""

ARM_SIMPLIFY_ROUNDS = 15
"""The same for a joint-space path: each shortcut tried is checked for collision along
its length, and the arm's checks are slow (a round takes ~7 ms in the Youbot scene and
~15 ms in the assembly cell)."""


@dataclass(frozen=True, slots=True)
class JointPlan:
    """A solved arm motion: joint vectors from start to goal, and OMPL's time."""

    path: tuple[tuple[float, ...], ...]
    seconds: float


def plan_joints(
    start: tuple[float, ...],
    goal: tuple[float, ...],
    valid: Callable[[tuple[float, ...]], bool],
    lower: tuple[float, ...],
    upper: tuple[float, ...],
    iterations: int = 2000,
) -> JointPlan | None:
    """Plan an arm motion in joint space (RealVectorStateSpace, RRTConnect, simplified).

    Used where the straight joint move collides. `valid(q)` is the arm's collision check.
    Returns None when no path is found within `iterations` of RRTConnect's.
    """
    ob, og = _ompl("base"), _ompl("geometric")
    n = len(start)
    space = ob.RealVectorStateSpace(n)
    box = ob.RealVectorBounds(n)
    for i in range(n):
        box.setLow(i, lower[i])
        box.setHigh(i, upper[i])
    space.setBounds(box)
    setup = og.SimpleSetup(space)

    def checker(state: Any) -> bool:
        return valid(tuple(state[i] for i in range(n)))

    setup.setStateValidityChecker(checker)
    info = setup.getSpaceInformation()
    info.setStateValidityCheckingResolution(0.002)  # a fraction of the space: ~0.02 rad
    s, g = space.allocState(), space.allocState()
    for i in range(n):
        s[i], g[i] = start[i], goal[i]
    setup.setStartAndGoalStates(s, g)
    setup.setPlanner(og.RRTConnect(info))
    began, work = time.perf_counter(), Work(iterations)
    try:
        if not (bool(setup.solve(work.condition())) and setup.haveExactSolutionPath()):
            return None
        setup.simplifySolution(Work(ARM_SIMPLIFY_ROUNDS).condition())
        raw = setup.getSolutionPath()
        points = tuple(tuple(raw.getState(k)[i] for i in range(n))
                       for k in range(raw.getStateCount()))
        return JointPlan(points, time.perf_counter() - began)
    finally:
        setup.clear()
        del setup, info, checker, s, g, space
