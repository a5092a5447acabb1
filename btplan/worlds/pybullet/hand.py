"""An external agent's hand: it comes down, takes a cube, carries it and drops it.

The scene's `move` and `remove` events act through it by default, so a cube moved by
someone else travels through the scene over several ticks and settles by physics where
it is dropped, instead of jumping. (`teleport` events still jump, for tests.) The hand
and the cube it carries move kinematically, one tick's worth per call to `advance`; the
drop is physical: the cube is let go a little above the floor and comes to rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from btplan.worlds.pybullet.scene import Point
from btplan.worlds.pybullet.sim import PARKED_Z
from btplan.worlds.pybullet.state import SceneState

HEIGHT = 0.9     # metres: the hand travels above the robot's arm
SPEED = 2.0      # metres per second
Position = tuple[float, float, float]


@dataclass(slots=True)
class Carry:
    """One cube on its way: the hand's waypoints, one per tick, and where it lets go."""

    name: str
    cube: str
    waypoints: list[Position]
    release: int                      # index of the waypoint where the cube is let go
    to: Point | None
    step: int = 0
    done: bool = False
    holding: bool = field(default=True)


class AgentHand:
    """The visible hand of the scene's external agents (one body, reused)."""

    def __init__(self, state: SceneState) -> None:
        self.state = state
        sim = state.sim
        p = sim.p
        visual = p.createVisualShape(p.GEOM_BOX, halfExtents=[0.05, 0.05, 0.03],
                                     rgbaColor=[0.25, 0.25, 0.3, 1.0],
                                     physicsClientId=sim.client)
        self.body = int(p.createMultiBody(0.0, -1, visual, [0.0, 0.0, PARKED_Z],
                                          physicsClientId=sim.client))
        self.carries: list[Carry] = []

    def take(self, name: str, cube: str, to: Point | None) -> None:
        """Start carrying `cube` to `to` (None: out of the scene)."""
        state = self.state
        size = state.scene.cube_size
        if state.present(cube) or cube in state.carried:
            x, y, _ = state.sim.cube_position(cube)
            start: Position = (x, y, size / 2)
        else:
            tx, ty = to if to is not None else (0.0, 0.0)
            start = (tx, ty, HEIGHT + 1.0)   # brought in from above
        if to is not None:
            end: Position = (to[0], to[1], size / 2 + 0.02)
        else:
            end = (start[0], start[1], HEIGHT + 1.0)
        legs = [start, (start[0], start[1], HEIGHT), (end[0], end[1], HEIGHT), end]
        waypoints = self._sample(legs)
        release = len(waypoints) - 1
        waypoints += self._sample([end, (end[0], end[1], HEIGHT + 1.0)])[1:]
        if state.held == cube:
            state.sim.robot.detach()     # taken out of the robot's hand
        self.carries.append(Carry(name, cube, waypoints, release, to))
        state.carried.add(cube)

    def _sample(self, legs: list[Position]) -> list[Position]:
        per_tick = SPEED * self.state.scene.tick_seconds
        out = [legs[0]]
        for a, b in zip(legs, legs[1:]):
            n = max(1, math.ceil(math.dist(a, b) / per_tick))
            out.extend(tuple(u + (v - u) * k / n for u, v in zip(a, b))  # type: ignore[misc]
                       for k in range(1, n + 1))
        return out

    @property
    def busy(self) -> bool:
        return any(not c.done for c in self.carries)

    def advance(self) -> list[str]:
        """Move every carry on by one tick; returns what finished, in words."""
        finished = []
        sim = self.state.sim
        sim.moved()
        p = sim.p
        for carry in self.carries:
            if carry.done:
                continue
            carry.step += 1
            at = carry.waypoints[min(carry.step, len(carry.waypoints) - 1)]
            p.resetBasePositionAndOrientation(self.body, [at[0], at[1], at[2] + 0.06],
                                              [0, 0, 0, 1], physicsClientId=sim.client)
            body = sim.cubes[carry.cube]
            if carry.holding:
                p.resetBasePositionAndOrientation(body, list(at), [0, 0, 0, 1],
                                                  physicsClientId=sim.client)
                p.resetBaseVelocity(body, [0, 0, 0], [0, 0, 0], physicsClientId=sim.client)
            if carry.step == carry.release:
                carry.holding = False    # let go: the physics does the rest
                self.state.carried.discard(carry.cube)
                if carry.to is None:
                    self.state.put(carry.cube, None)
                where = "out of the scene" if carry.to is None else f"at {carry.to}"
                finished.append(f"{carry.name}: {carry.cube} let go {where}")
            if carry.step >= len(carry.waypoints) - 1:
                carry.done = True
                p.resetBasePositionAndOrientation(self.body, [0, 0, PARKED_Z], [0, 0, 0, 1],
                                                  physicsClientId=sim.client)
        sim.moved()
        return finished
