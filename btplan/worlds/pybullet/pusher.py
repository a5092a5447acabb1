"""The external agents' robot: a small pusher that drives in and pushes a cube by contact.

The scene's `move` and `remove` events act through it, so a cube moved by someone else
travels over the floor, pushed by a body the physics engine knows about, and comes to
rest where the push ends (`teleport` events still make cubes jump, for tests). The
pusher is a dynamic body with a U-shaped front pocket that keeps the cube centred. It is
driven by velocity, set before every physics step: it drives in from outside the scene
along an OMPL path that avoids walls, cubes and the robot, turns to face the push, pushes
the cube along a straight line until the cube's centre reaches the target, backs off and
drives out again (or, with no free way out, leaves the scene at once). A push that makes
no progress (a wall, the robot) is given up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.scene import Point
from btplan.worlds.pybullet.sim import HZ, PARKED_Z
from btplan.worlds.pybullet.state import SceneState

DRIVE_SPEED = 2.0     # m/s driving in and out
PUSH_SPEED = 1.2      # m/s pushing a cube
TURN_RATE = 4.0       # rad/s
RADIUS = 0.17         # m: the pusher's footprint for its own path planning
BEHIND = 0.3          # m between the cube and the pusher's pocket where a push starts
OUTSIDE = 0.6         # m beyond the scene's bounds where the pusher waits
STALL_SECONDS = 0.6   # a push that gains less than STALL_GAIN in this long is given up
STALL_GAIN = 0.01
MASS = 3.0
PLAY = 0.006          # m between a cube and each side of the pocket
ESCAPE = 0.3          # m the pusher may move straight off a start too close to the robot
PUSHER_ITERATIONS = 100  # RRTConnect iterations for the pusher's way in or out (~5 ms each;
                         # a way is found in a few, or the pusher drives straight)
Job = tuple[str, str, Point | None, bool]
"""An event's name, its cube, where to push it (None: out of the scene) and whether the
cube leaves the scene at the end."""


@dataclass(slots=True)
class Push:
    """The push under way: its line, where it stands, and what the pusher does now."""

    name: str
    cube: str
    to: Point
    remove: bool
    home: Point
    heading: float
    route: list[Point] = field(default_factory=list)
    phase: str = "in"             # in, turn, push, back, out
    best: float = math.inf        # the least distance left so far (stall detection)
    since: int = 0                # physics steps since `best` last improved


class Pusher:
    """One pusher body for all the scene's push events, taken one after the other."""

    def __init__(self, state: SceneState) -> None:
        self.state = state
        sim = state.sim
        self.p: Any = sim.p
        self.client = sim.client
        self.body = self._build()
        self.jobs: list[Job] = []
        self.push: Push | None = None
        self.finished: list[str] = []
        self.plan_seconds = 0.0
        sim.controllers.append(self.control)

    def _build(self) -> int:
        """A back plate and two side plates (the pocket), and a mast to be seen by."""
        p, c = self.p, self.client
        pocket = self.state.scene.cube_size / 2 + PLAY      # half its inner width
        half = [[0.03, 0.12, 0.05], [0.035, 0.015, 0.05], [0.035, 0.015, 0.05]]
        where = [[-0.03, 0.0, 0.0], [0.035, pocket + 0.015, 0.0], [0.035, -pocket - 0.015, 0.0]]
        shape = p.createCollisionShapeArray([p.GEOM_BOX] * 3, halfExtents=half,
                                            collisionFramePositions=where, physicsClientId=c)
        colour = [0.45, 0.2, 0.55, 1.0]
        visual = p.createVisualShapeArray(
            [p.GEOM_BOX] * 4, halfExtents=[*half, [0.03, 0.03, 0.12]],
            visualFramePositions=[*where, [-0.04, 0.0, 0.15]],
            rgbaColors=[colour] * 3 + [[0.9, 0.9, 0.95, 1.0]], physicsClientId=c)
        body = int(p.createMultiBody(MASS, shape, visual, [0.0, 0.0, PARKED_Z],
                                     physicsClientId=c))
        # Frictionless: the velocity set on every step drives it, and a cube slides
        # freely along the pocket's walls instead of being dragged sideways.
        p.changeDynamics(body, -1, lateralFriction=0.0, spinningFriction=0.0,
                         rollingFriction=0.0, physicsClientId=c)
        return body

    # --- jobs ----------------------------------------------------------------------------

    def take(self, name: str, cube: str, to: Point | None, origin: Point | None,
             remove: bool) -> str:
        """Queue a push of `cube` to `to` (None: off the scene); a cube not in the scene
        is first set down at `origin`, outside it, where the pusher picks it up."""
        state = self.state
        if state.held == cube:
            return f"{name}: {cube} is in the robot's hand; the pusher leaves it"
        if not state.present(cube):
            start = origin if origin is not None else self._outside(to or (0.0, 0.0))
            state.sim.place_cube(cube, start)
        self.jobs.append((name, cube, to, remove))
        where = "out of the scene" if to is None else f"to {list(to)}"
        return f"{name}: the pusher sets off to push {cube} {where}"

    @property
    def busy(self) -> bool:
        """Whether a push is under way or queued: Shove starts no new one until it is not."""
        return self.push is not None or bool(self.jobs)

    def news(self) -> list[str]:
        """What finished since the last call, in words."""
        out, self.finished = self.finished, []
        return out

    def _outside(self, at: Point) -> Point:
        """The point OUTSIDE metres beyond the bounds' edge nearest to `at`."""
        x0, x1, y0, y1 = self.state.scene.bounds
        x, y = at
        edges = [(x - x0, (x0 - OUTSIDE, y)), (x1 - x, (x1 + OUTSIDE, y)),
                 (y - y0, (x, y0 - OUTSIDE)), (y1 - y, (x, y1 + OUTSIDE))]
        return min(edges)[1]

    def _start(self) -> None:
        name, cube, to, remove = self.jobs.pop(0)
        state = self.state
        x, y, _ = state.sim.cube_position(cube)
        if to is None:
            base = state.base
            away = (x - base[0], y - base[1])
            norm = math.hypot(*away) or 1.0
            to = self._edge((x, y), (away[0] / norm, away[1] / norm))
            remove = True
        heading = math.atan2(to[1] - y, to[0] - x)
        d = (math.cos(heading), math.sin(heading))
        stage = (x - d[0] * BEHIND, y - d[1] * BEHIND)
        # It comes in from outside the scene: straight along the line when the cube
        # waits outside (it was brought in), else from the nearest edge.
        outside = not state.sim.in_bounds(*stage, 0.0)
        home = (stage[0] - d[0] * BEHIND, stage[1] - d[1] * BEHIND) if outside \
            else self._outside(stage)
        push = Push(name, cube, to, remove, home, heading)
        here, _ = self._pose()
        if self.push is None:                # it enters the scene at `home`
            here = home
            self._put(home, math.atan2(stage[1] - home[1], stage[0] - home[0]))
        # No free way in: straight along the line, and the physics decides what it bumps.
        push.route = self._route(here, stage) or [stage]
        self.push = push

    def _edge(self, at: Point, d: Point) -> Point:
        """Where the ray from `at` along `d` leaves the bounds, OUTSIDE metres beyond."""
        x0, x1, y0, y1 = self.state.scene.bounds
        steps = [((x1 if d[0] > 0 else x0) - at[0]) / d[0] if abs(d[0]) > 1e-9 else math.inf,
                 ((y1 if d[1] > 0 else y0) - at[1]) / d[1] if abs(d[1]) > 1e-9 else math.inf]
        k = min(steps) + OUTSIDE
        return (at[0] + d[0] * k, at[1] + d[1] * k)

    def _route(self, start: Point, goal: Point) -> list[Point] | None:
        """An OMPL path for the pusher's disc (walls, cubes and the robot avoided), or
        None when there is none."""
        state, sim = self.state, self.state.sim
        x0, x1, y0, y1 = state.scene.bounds
        wide = (x0 - 2 * OUTSIDE, x1 + 2 * OUTSIDE, y0 - 2 * OUTSIDE, y1 + 2 * OUTSIDE)
        robot = state.base
        cubes = [state.sim.cube_position(c)[:2] for c in state.cube_names if state.present(c)]
        reach = state.scene.robot_radius + RADIUS

        def valid(x: float, y: float) -> bool:
            if math.hypot(x - robot[0], y - robot[1]) < reach:
                return False
            if any(math.hypot(x - cx, y - cy) < RADIUS + 0.05 for cx, cy in cubes):
                return False
            return all(_box_gap(x, y, sim.extent[w]) > RADIUS for w in sim.walls)

        # A push ends beside the robot, within the disc kept around it: leave that start
        # first (motion.escape), or OMPL finds no way out and the pusher drives out in a
        # straight line, shoving any cube on it out of the scene.
        here = (*start, 0.0) if valid(*start) else motion.escape((*start, 0.0), valid, ESCAPE)
        if here is None:
            return None
        plan = motion.plan_se2(here, (*goal, 0.0), valid, wide, PUSHER_ITERATIONS)
        if plan is None:
            return None
        self.plan_seconds += plan.seconds
        lead = [] if here[:2] == start else [(here[0], here[1])]
        return lead + [(q[0], q[1]) for q in plan.path[1:]]

    # --- control, before every physics step ----------------------------------------------

    def control(self) -> None:
        """Set the pusher's velocity for the next physics step (it is one of `sim.controllers`).

        The next queued job starts once the current push is backing off or driving out;
        otherwise the push's phase says whether to drive, turn or push.
        """
        if self.jobs and (self.push is None or self.push.phase in ("back", "out")):
            self._start()                    # the next job, from wherever the pusher is
        if self.push is None:
            return
        push = self.push
        assert push is not None
        (x, y), yaw = self._pose()
        if push.phase in ("in", "out"):
            self._drive(push, (x, y), yaw)
        elif push.phase == "turn":
            if self._turn(yaw, push.heading):
                push.phase = "push"
        elif push.phase == "push":
            self._push(push, (x, y))
        elif push.phase == "back":
            self._drive(push, (x, y), yaw)

    def _drive(self, push: Push, at: Point, yaw: float) -> None:
        if not push.route:
            self._arrived(push)
            return
        target = push.route[0]
        gap = distance(at, target)
        if gap < 0.02:
            push.route.pop(0)
            return
        heading = math.atan2(target[1] - at[1], target[0] - at[0])
        if push.phase == "back":
            heading = push.heading           # backs off facing the cube
        if not self._turn(yaw, heading, moving=True):
            return
        speed = min(DRIVE_SPEED, gap * HZ / 4)
        self._velocity(((target[0] - at[0]) / gap * speed, (target[1] - at[1]) / gap * speed),
                       0.0 if push.phase == "back" else self._turn_rate(yaw, heading))

    def _arrived(self, push: Push) -> None:
        if push.phase == "in":
            push.phase = "turn"
        elif push.phase == "back":
            push.phase = "out"
            (x, y), _ = self._pose()
            route = self._route((x, y), push.home)
            if route is None:
                # No free way out (cubes and walls close round it): it leaves the scene
                # at once. Driven out in a straight line, it shoved whatever lay on the
                # line across the floor, 3 m into a corner no robot pose reaches.
                self._park()
            else:
                push.route = route
        else:                                # out of the scene: park until the next job
            self._park()

    def _push(self, push: Push, at: Point) -> None:
        """Drive along the line; stop once the cube's centre is at the target."""
        cx, cy, _ = self.state.sim.cube_position(push.cube)
        d = (math.cos(push.heading), math.sin(push.heading))
        left = (push.to[0] - cx) * d[0] + (push.to[1] - cy) * d[1]
        lateral = abs(-(push.to[0] - cx) * d[1] + (push.to[1] - cy) * d[0])
        if left <= 0.003 or lateral > 0.3:
            self._done(push, "pushed to" if lateral <= 0.3 else "lost on the way at")
            return
        if left < push.best - STALL_GAIN:
            push.best, push.since = left, 0
        push.since += 1
        if push.since > STALL_SECONDS * HZ:
            self._done(push, "stuck at")
            return
        self.state.sim.outside_changes += 1
        speed = min(PUSH_SPEED, max(0.05, left * 3.0))
        # Steer back onto the line through the target, so the cube ends where it should.
        off = (push.to[0] - at[0]) * -d[1] + (push.to[1] - at[1]) * d[0]
        (_, _), yaw = self._pose()
        self._velocity((d[0] * speed - d[1] * off * 2.0, d[1] * speed + d[0] * off * 2.0),
                       self._turn_rate(yaw, push.heading))

    def _done(self, push: Push, how: str) -> None:
        state = self.state
        x, y, _ = state.sim.cube_position(push.cube)
        self._velocity((0.0, 0.0), 0.0)
        gone = push.remove and not state.sim.in_bounds(x, y, 0.0)
        if gone:
            state.put(push.cube, None)
            self.finished.append(f"{push.name}: {push.cube} pushed out of the scene")
        else:
            self.finished.append(f"{push.name}: {push.cube} {how} [{x:.2f}, {y:.2f}]")
        (px, py), _ = self._pose()
        d = (math.cos(push.heading), math.sin(push.heading))
        push.phase = "back"
        push.route = [(px - d[0] * 0.2, py - d[1] * 0.2)]

    # --- the body ------------------------------------------------------------------------

    def _pose(self) -> tuple[Point, float]:
        pos, orn = self.p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
        yaw = self.p.getEulerFromQuaternion(orn)[2]
        return (float(pos[0]), float(pos[1])), float(yaw)

    def _turn_rate(self, yaw: float, heading: float) -> float:
        error = math.remainder(heading - yaw, math.tau)
        return max(-TURN_RATE, min(TURN_RATE, error * HZ / 4))

    def _turn(self, yaw: float, heading: float, moving: bool = False) -> bool:
        """Turn on the spot towards `heading`; True once it faces it (within 0.1 rad)."""
        if abs(math.remainder(heading - yaw, math.tau)) < (0.1 if moving else 0.02):
            return True
        self._velocity((0.0, 0.0), self._turn_rate(yaw, heading))
        return False

    def _velocity(self, linear: Point, turn: float) -> None:
        p = self.p
        v, _ = p.getBaseVelocity(self.body, physicsClientId=self.client)
        p.resetBaseVelocity(self.body, [linear[0], linear[1], min(0.0, v[2])],
                            [0.0, 0.0, turn], physicsClientId=self.client)

    def _park(self) -> None:
        """Out of the scene until the next job."""
        self._put((0.0, 0.0), 0.0, PARKED_Z)
        self.push = None

    def _put(self, at: Point, yaw: float, z: float = 0.051) -> None:
        """Set the pusher down (entering the scene from outside) or park it (at rest)."""
        p = self.p
        p.resetBasePositionAndOrientation(self.body, [at[0], at[1], z],
                                          p.getQuaternionFromEuler([0.0, 0.0, yaw]),
                                          physicsClientId=self.client)
        p.resetBaseVelocity(self.body, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)


def _box_gap(x: float, y: float, box: tuple[float, float, float, float]) -> float:
    cx, cy, hx, hy = box
    return math.hypot(max(abs(x - cx) - hx, 0.0), max(abs(y - cy) - hy, 0.0))

