"""Trajectories: OMPL paths the planner refers to by name, re-checked against the scene.

A trajectory leads to a location (a cube, a region, a sampled pose). Its path is planned
from where the robot is when it is needed: a path computed while the robot stood
elsewhere is joined to the robot's pose, or planned again, before it is checked or
followed, so `free(t)` always speaks about the path the robot would actually drive. Paths avoid walls; movable cubes are
avoided when a detour exists, and otherwise the path goes through them and the cubes on
it are reported as blocking, which is what makes the tree expand (the paper's Example 2).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.motion import Pose2

DRIVE_FROM = 0.05    # metres the robot may be off a path's start when it starts driving it
CHECK_FROM = 0.5     # the same when only checking the path: the way ahead barely changes
STALE_GOAL = 0.05    # metres the target may have moved before the path is re-planned


@dataclass(slots=True)
class Trajectory:
    """A named path to `target`; `clearing` holds cubes the planner was told block it.

    A cube in `clearing` keeps the trajectory blocked while it is held, and stops
    counting once it rests somewhere off the path: carrying an obstacle is not yet
    having removed it (the paper's Place-aside step).
    """

    name: str
    target: str
    path: tuple[Pose2, ...] = ()
    goal: Pose2 | None = None
    clearing: set[str] = field(default_factory=set)
    executing: bool = False
    plans: int = 0
    layout: object = None

    def stale(self, robot: Pose2, goal: Pose2 | None, layout: object,
              slack: float = CHECK_FROM) -> bool:
        """Planned from elsewhere, towards a target that moved, or among other cubes."""
        if self.executing:
            return False
        if not self.path or goal is None or self.goal is None or layout != self.layout:
            return True
        return distance(self.path[0], robot) > slack or distance(self.goal, goal) > STALE_GOAL
