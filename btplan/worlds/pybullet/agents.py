"""Scripted external agents: the scene's events, fired at a tick or when a condition holds.

The paper's Youbot experiment has two agents that move cubes while the robot works; a
scene lists such events so that a user can change the story without code. Each event
fires once. A `when` event watches a literal through the world's own `check`, counts the
ticks on which it becomes true, and fires `delay` ticks after the `count`-th time.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from btplan.errors import InputError, Span
from btplan.worlds.agents import Disturbance
from btplan.worlds.pybullet.scene import Event

if TYPE_CHECKING:
    from btplan.worlds.pybullet.world import PyBulletWorld


def parse_literal(text: str, where: Span | None) -> tuple[bool, str, tuple[str, ...]]:
    """`holding(green)` or `not near(goal)` as (positive, predicate, args)."""
    body = text.strip()
    positive = not body.startswith("not ")
    body = body.removeprefix("not ").strip()
    name, _, rest = body.partition("(")
    if not name.isidentifier() or (rest and not rest.endswith(")")):
        raise InputError(f"cannot read the condition {text!r}", where,
                         "write it as in the domain, e.g. holding(green) or not near(goal)")
    args = tuple(a.strip() for a in rest[:-1].split(",") if a.strip()) if rest else ()
    return positive, name, args


@dataclass(slots=True)
class ScriptedEvent:
    """One event of the scene and its progress (edge count, tick it is due)."""

    event: Event
    literal: tuple[bool, str, tuple[str, ...]] | None
    seen: int = 0
    was_true: bool = False
    due: int | None = None
    done: bool = False

    def act(self, world: PyBulletWorld, tick: int) -> list[str]:
        """Fire the event when it is due; returns what happened, in words."""
        if self.done:
            return []
        if self.due is None:
            self.due = self._due(world, tick)
        if self.due is None or tick < self.due:
            return []
        self.done = True
        return [apply(world, self.event)]

    def _due(self, world: PyBulletWorld, tick: int) -> int | None:
        if self.event.tick is not None:
            return self.event.tick
        if self.literal is None:
            return None
        positive, name, args = self.literal
        now = world.check((name, args)) is positive
        if now and not self.was_true:
            self.seen += 1
        self.was_true = now
        return tick + self.event.delay if self.seen >= self.event.count else None


@dataclass(slots=True)
class SceneAgents:
    """All scripted events of a scene, acting as one external agent."""

    events: list[ScriptedEvent] = field(default_factory=list)
    log: list[Disturbance] = field(default_factory=list)
    name: str = "scene"

    def act(self, world: PyBulletWorld, tick: int) -> list[Disturbance]:
        happened = [Disturbance(tick, self.name, text, "scene")
                    for e in self.events for text in e.act(world, tick)]
        self.log.extend(happened)
        return happened


def scene_agents(events: tuple[Event, ...], path: str) -> SceneAgents:
    scripted = []
    for event in events:
        literal = parse_literal(event.when, Span(path, 1, 1)) if event.when else None
        scripted.append(ScriptedEvent(event, literal))
    return SceneAgents(scripted)


def apply(world: PyBulletWorld, event: Event) -> str:
    """Carry out one event on the world and describe it."""
    cube = event.cube
    if event.do == "move":
        world.put(cube, event.to)
        return f"{event.name}: {cube} moved to {event.to}"
    if event.do == "remove":
        world.put(cube, None)
        return f"{event.name}: {cube} removed"
    if world.held == cube:
        world.put(cube, world.sim.gripper_point())
        return f"{event.name}: {cube} slipped from the gripper"
    return f"{event.name}: {cube} was not in the gripper"
