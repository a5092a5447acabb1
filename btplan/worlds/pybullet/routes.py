"""Named trajectories for the base: planned with OMPL; when they went stale, joined to
the robot and the new goal by straight lines if those are free, planned again otherwise.

Built on the scene state and the samplers (the approach pose at a trajectory's end);
the conditions, the skills and refinement use it.
"""

from __future__ import annotations

import itertools
import math
import time

from btplan.worlds.pybullet import motion, samplers
from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.paths import CHECK_FROM, DRIVE_FROM, STALE_GOAL, Trajectory
from btplan.worlds.pybullet.scene import Point
from btplan.worlds.pybullet.state import SceneState

STEP = 0.05          # metres between waypoints of a path
PLAN_ITERATIONS = 3000    # RRTConnect iterations for a path that avoids walls only (~100 us
                          # each; solves take a few dozen, hundreds at the most)
DETOUR_ITERATIONS = 1000  # for a path that also avoids the movable cubes
JOIN = CHECK_FROM    # metres a stale path may be joined over, from the robot or to the goal
JOIN_BACK = 2 * round(JOIN / STEP)  # waypoints back from the end where the goal join may start
ESCAPE = 0.15        # metres the robot may move off a start where its disc touches a wall or
                     # a cube, to the nearest pose where it does not (motion.escape)


class Routes:
    """Plans and re-plans the trajectories of `state`; keeps OMPL's timings for the stats."""

    def __init__(self, state: SceneState) -> None:
        self.state = state
        self.plan_seconds: list[float] = []
        self._counter = itertools.count(1)
        self._no_detour: set[tuple[object, ...]] = set()
        self._no_path: set[tuple[object, ...]] = set()
        self.refreshed = 0  # poses sampled again because they went stale
        self.joined = 0  # stale paths kept, joined to the robot and to the goal instead
        self.escaped = 0  # paths planned from a start the disc grazed, led out of it first
        self.last_blockers: dict[str, frozenset[str]] = {}
        """The cubes last measured on each path: the facts report them for a path not
        measured now (planned from elsewhere), so that they do not flicker as the robot moves."""

    def new_trajectory(self, target: str) -> str:
        """Name a new trajectory to `target` (`traj1`, `traj2`, ...) and plan it from here.

        The name is the value RefineActions gives the planner; the path behind it may change.
        """
        name = f"traj{next(self._counter)}"
        self.state.trajectories[name] = Trajectory(name, target)
        self.prepare(name)
        return name

    def sample_pose(self) -> str | None:
        """Reserve a spot off every known path to put an obstacle, and name it."""
        spot = self._aside(None)
        if spot is None:
            return None
        name = f"pose{len(self.state.poses) + 1}"
        self.state.poses[name] = spot
        return name

    def refresh_pose(self, name: str) -> None:
        """Sample a pose again, under its name, if it went stale: RefineActions once more.

        A pose chosen earlier may now be taken by a cube, or lie on a path planned since;
        the grounded action keeps its name and gets a value from the world as it is now.
        """
        state = self.state
        spot = state.poses.get(name)
        if spot is None or samplers.aside_fits(state, spot, self._paths(name), name):
            return
        fresh = self._aside(name)
        if fresh is not None:
            state.poses[name] = fresh
            self.refreshed += 1

    def _paths(self, pose: str | None) -> list[tuple[Pose2, ...]]:
        """The known paths, except those that lead to `pose` itself."""
        return [t.path for t in self.state.trajectories.values() if t.path and t.target != pose]

    def _aside(self, pose: str | None) -> Point | None:
        spot = samplers.aside_spot(self.state, self._paths(pose), pose)
        if spot is None:  # every spot is near some path: keep off those to cubes and regions
            poses = self.state.poses
            paths = [t.path for t in self.state.trajectories.values()
                     if t.path and t.target not in poses]
            spot = samplers.aside_spot(self.state, paths, pose)
        return spot

    def blockers(self, name: str) -> frozenset[str]:
        """The cubes that block trajectory `name` now ("(no path)" if it has none).

        A cube seen on the path keeps blocking it while the robot holds it: picking an
        obstacle up is not yet having put it aside (only Place achieves that).
        """
        traj = self.state.trajectories.get(name)
        if traj is None:
            return frozenset({"(no path)"})
        self.prepare(name)
        found = frozenset(self.state.blockers(traj))
        traj.clearing.update(c for c in found if c in self.state.sim.cubes)
        self.last_blockers[name] = found
        return found

    def prepare(self, name: str, slack: float = CHECK_FROM) -> None:
        """Plan the trajectory again if it was planned from elsewhere or its target moved.

        `slack` is how far from the path's start the robot may be: small when the robot is
        about to drive the path, larger when the path is only checked, which saves most
        re-planning while the robot drives elsewhere.
        """
        state = self.state
        traj = state.trajectories[name]
        if traj.target in state.sim.cubes and not state.present(traj.target):
            return  # a cube taken out of the scene: keep the old path, nothing to reach
        goal = samplers.approach_pose(state, traj.target) or \
            samplers.approach_pose(state, traj.target, avoid_cubes=False)
        if not traj.stale(state.base, goal, state.layout(), slack) or goal is None:
            return
        joined = self._join(traj, goal)
        if joined is not None:
            traj.path, traj.goal = joined, goal
            self.joined += 1
            return
        path = self._plan(traj.target, goal)
        traj.plans += 1
        if not path and traj.path and slack > DRIVE_FROM:
            # Only checked, not driven: no path from exactly here (the base grazes a wall
            # as it turns) keeps the last one, still stale, to plan again from the next spot.
            return
        traj.path, traj.goal = path, goal
        traj.layout = state.layout()

    def _join(self, traj: Trajectory, goal: Pose2) -> tuple[Pose2, ...] | None:
        """The stale path, joined by straight lines from the robot and to the new goal.

        A path the robot only drove off, or whose target moved a little, is still a way
        there: the robot steps onto its nearest waypoint and leaves it where the goal is
        in a straight line. Both joins must be free of walls and cubes, and the robot must
        not have moved a cube since the path was planned; otherwise OMPL plans again.
        """
        state, path = self.state, traj.path
        if not path or traj.goal is None or traj.layout != state.layout() \
                or distance(traj.goal, goal) > JOIN:
            return None
        robot = state.base
        first = min(range(len(path)), key=lambda i: (distance(path[i], robot), -i))
        if distance(path[first], robot) > JOIN:
            return None
        cubes = state.floor_cubes(traj.target, state.held)
        if not self._line_free(robot, path[first], cubes):
            return None
        head = motion.densify([robot[:2], path[first][:2]], robot, path[first], STEP)[:-1]
        if distance(traj.goal, goal) <= STALE_GOAL:
            return head + path[first:]
        for last in range(len(path) - 1, max(first, len(path) - 1 - JOIN_BACK) - 1, -1):
            if self._line_free(path[last], goal, cubes):
                tail = motion.densify([path[last][:2], goal[:2]], path[last], goal, STEP)
                return head + path[first:last] + tail
        return None

    def _line_free(self, a: Pose2, b: Pose2, cubes: list[str]) -> bool:
        """The robot's disc fits everywhere on the segment from `a` to `b` (every half step)."""
        n = max(1, math.ceil(distance(a, b) / (STEP / 2)))
        sim = self.state.sim
        return all(sim.base_free(a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n, cubes)
                   for k in range(n + 1))

    def _plan(self, target: str, goal: Pose2) -> tuple[Pose2, ...]:
        state = self.state
        start = state.base
        # A path OMPL did not find stays unfound for a while: remember the question, or a
        # path checked every tick would spend its whole budget on every tick.
        question = (target, tuple(round(v, 1) for v in goal), round(start[0], 1),
                    round(start[1], 1))
        if question in self._no_path:
            return ()
        walls_only = self._solve(start, goal, [], PLAN_ITERATIONS)
        if walls_only is None:
            self._no_path.add(question)
            return ()
        path = walls_only
        cubes = state.floor_cubes(target, state.held)
        if any(state.on_path(c, path, 0) for c in cubes):
            layout = (target, tuple((c, tuple(round(v, 2) for v in state.location(c)))
                                    for c in cubes),
                      round(start[0], 1), round(start[1], 1))
            if layout not in self._no_detour:
                detour = self._solve(start, goal, cubes, DETOUR_ITERATIONS)
                if detour is None:
                    self._no_detour.add(layout)
                else:
                    path = detour
        return path

    def _solve(self, start: Pose2, goal: Pose2, cubes: list[str], iterations: int
               ) -> tuple[Pose2, ...] | None:
        valid = self.state.sim.base_checker(cubes)
        began = time.perf_counter()
        free = start if valid(start[0], start[1]) else motion.escape(start, valid, ESCAPE)
        if free is None or not valid(goal[0], goal[1]):
            return None  # OMPL would spend its whole budget before saying so
        result = motion.plan_se2(free, goal, valid, self.state.scene.bounds, iterations,
                                  STEP)
        self.plan_seconds.append(time.perf_counter() - began)  # failed solves count too
        if result is None:
            return None
        if free is not start:  # leave the grazing start first (motion.escape)
            self.escaped += 1
            head = motion.densify([start[:2], free[:2]], start, free, STEP)[:-1]
            return head + result.path
        return result.path
