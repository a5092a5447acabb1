"""Scripted external agents: the scene's events, fired at a tick or when a condition holds.

The paper's Youbot experiment has two agents that move cubes while the robot works; a
scene lists such events so that a user can change the story without code. Each event
fires once. `move` and `remove` act physically, through the pusher robot (pusher.py);
`knock` sets a cube moving (off a shelf) and leaves the rest to the physics; `slip` and
`teleport` act on the scene directly. A `when` event watches a literal through the
world's own `check`, counts the ticks on which it becomes true, and fires `delay` ticks
after the `count`-th time.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from difflib import get_close_matches
from pathlib import Path

from btplan.errors import InputError, Span
from btplan.limits import shorten
from btplan.worlds.agents import Disturbance
from btplan.worlds.pybullet.pusher import Pusher
from btplan.worlds.pybullet.scene import Event
from btplan.worlds.pybullet.state import SceneState

Check = Callable[[tuple[str, tuple[str, ...]]], bool]
"""How an event watches a condition: the world's own `check`."""


def parse_literal(text: str, where: Span | None) -> tuple[bool, str, tuple[str, ...]]:
    """`holding(green)` or `not near(goal)` as (positive, predicate, args)."""
    body = text.strip()
    positive = not body.startswith("not ")
    body = body.removeprefix("not ").strip()
    name, _, rest = body.partition("(")
    if not name.isidentifier() or (rest and not rest.endswith(")")):
        raise InputError(f"cannot read the condition {shorten(repr(text))}", where,
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

    def act(self, world: SceneState, pusher: Pusher | None, check: Check,
            tick: int) -> list[str]:
        """Fire the event when it is due; returns what happened, in words."""
        if self.done:
            return []
        if self.due is None:
            self.due = self._due(check, tick)
        if self.due is None or tick < self.due:
            return []
        self.done = True
        return [apply(world, pusher, self.event)]

    def _due(self, check: Check, tick: int) -> int | None:
        if self.event.tick is not None:
            return self.event.tick
        if self.literal is None:
            return None
        positive, name, args = self.literal
        now = check((name, args)) is positive
        if now and not self.was_true:
            self.seen += 1
        self.was_true = now
        return tick + self.event.delay if self.seen >= self.event.count else None


@dataclass(slots=True)
class SceneAgents:
    """All scripted events of a scene, acting as one external agent.

    It is bound to the scene state and the world's `check` when the world is built
    (`bind`); the `world` argument of `act`, which the acting loop passes to every agent,
    is not needed.
    """

    events: list[ScriptedEvent] = field(default_factory=list)
    log: list[Disturbance] = field(default_factory=list)
    name: str = "scene"
    state: SceneState | None = None
    check: Check | None = None
    pusher: Pusher | None = None

    def bind(self, state: SceneState, check: Check) -> None:
        """Attach to the scene state and the world's `check`, once the world exists.

        A pusher is built only when some event moves or removes a cube: it is one more body
        for the physics to step.
        """
        self.state, self.check = state, check
        if any(e.event.do in ("move", "remove") for e in self.events):
            self.pusher = Pusher(state)

    def act(self, world: object, tick: int) -> list[Disturbance]:
        """Fire the events due at `tick`, and report the pushes that ended since the last tick.

        `world` is not used (the bound state is); before `bind`, nothing happens.
        """
        if self.state is None or self.check is None:
            return []
        state, check = self.state, self.check
        happened = [Disturbance(tick, self.name, text, "scene")
                    for e in self.events for text in e.act(state, self.pusher, check, tick)]
        if self.pusher is not None:
            happened += [Disturbance(tick, self.name, text, "scene")
                         for text in self.pusher.news()]
        self.log.extend(happened)
        return happened


def scene_agents(events: tuple[Event, ...], path: str,
                 predicates: Mapping[str, int] | None = None) -> SceneAgents:
    """The scene's events as one agent; `when` conditions must use the domain's predicates."""
    lines = _lines(path)
    scripted = []
    for event in events:
        literal = None
        if event.when:
            where, source = _locate(lines, path, event.when)
            literal = parse_literal(event.when, where)
            _, name, args = literal
            if predicates is not None and predicates.get(name) != len(args):
                known = sorted(predicates)
                near = get_close_matches(name, known, n=1)
                hint = f"did you mean '{near[0]}'?" if near and near[0] != name else (
                    f"{shorten(name)} takes {predicates[name]} arguments"
                    if name in predicates else None)
                raise InputError(f"event '{shorten(event.name)}': {shorten(repr(event.when))} "
                                 "is not a condition of the domain", where, hint, source)
        scripted.append(ScriptedEvent(event, literal))
    return SceneAgents(scripted)


def _lines(path: str) -> list[str]:
    try:
        return Path(path).read_text(encoding="utf-8").split("\n")
    except (OSError, ValueError):
        return []


def _locate(lines: list[str], path: str, text: str) -> tuple[Span, str | None]:
    for number, line in enumerate(lines, 1):
        column = line.find(text)
        if column >= 0:
            return Span(path, number, column + 1), line
    return Span(path, 1, 1), None


def apply(world: SceneState, pusher: Pusher | None, event: Event) -> str:
    """Carry out one event on the world (or start it, for the pusher) and describe it."""
    cube = event.cube
    if event.do == "teleport":
        world.put(cube, event.to)
        return f"{event.name}: {cube} teleported to {event.to}"
    if event.do == "knock" and event.origin is not None and event.to is not None:
        world.sim.knock(cube, event.origin, event.to)
        world.sim.outside_changes += 1
        return f"{event.name}: {cube} knocked off at {event.origin} towards {event.to}"
    if event.do in ("move", "remove") and pusher is not None:
        return pusher.take(event.name, cube, event.to, event.origin, event.do == "remove")
    if world.held == cube:
        world.sim.robot.slip()
        world.sim.moved()
        return f"{event.name}: {cube} slipped from the gripper"
    return f"{event.name}: {cube} was not in the gripper"


SPOT_TRIES = 20
"""Random spots tried for a shoved cube before the agent gives up for this tick."""
PUSH_STEP = 0.05
"""Metres between the points of a push's line checked for walls (a wall is 0.2 m thick)."""


class Shove:
    """At rate `rate` per tick, a pusher of its own pushes a cube the robot does not hold
    to a random free spot of the floor: the simulator's counterpart of the symbolic
    scenarios' agents, for sweeps over a rate (`--scenario shove`).

    It draws from its own stream seeded by the run's seed, three numbers every tick
    whatever happens, and binds to the world it is first given (the acting loop passes
    the world to every agent). A push takes many ticks; no new one starts until it ends.
    """

    name = "shove"

    def __init__(self, rate: float, seed: int) -> None:
        self.rate = rate
        self.rng = random.Random(seed * 7919 + 303)
        self.pusher: Pusher | None = None

    def act(self, world: object, tick: int) -> list[Disturbance]:
        """Perhaps start a push of a loose cube at `tick`; report the pushes that ended.

        The three draws come first, so the stream stays aligned whether or not a push starts;
        a world without a PyBullet scene state is left alone.
        """
        fire, pick, spot_seed = self.rng.random(), self.rng.random(), self.rng.random()
        state = getattr(world, "state", None)
        if not isinstance(state, SceneState):
            return []
        if self.pusher is None:
            self.pusher = Pusher(state)
        done = [Disturbance(tick, self.name, t, "scene") for t in self.pusher.news()]
        if fire >= self.rate or self.pusher.busy:
            return done
        cubes = sorted(set(state.floor_cubes()) - state.carried - {state.held})
        if not cubes:
            return done
        cube = cubes[int(pick * len(cubes))]
        spot = _free_spot(state, cube, spot_seed)
        if spot is not None:
            started = self.pusher.take(f"shove {cube}", cube, spot, None, False)
            done.append(Disturbance(tick, self.name, started, "scene"))
        return done


def _free_spot(state: SceneState, cube: str, seed: float) -> tuple[float, float] | None:
    """A random spot of the floor where `cube` fits, away from the robot, that a straight
    push gets it to: a target behind a wall would leave the cube pressed against the wall,
    where no hand fits round it, and the run would test the arm rather than the tree."""
    rng = random.Random(seed)
    x0, x1, y0, y1 = state.scene.bounds
    others = [c for c in state.floor_cubes(cube) if c not in state.carried]
    keep = state.scene.robot_radius + state.scene.cube_size
    start = state.location(cube)
    for _ in range(SPOT_TRIES):
        x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
        if (math.dist((x, y), state.base[:2]) > keep
                and state.sim.cube_fits(x, y, others)
                and _straight_push(state, start, (x, y))):
            return (x, y)
    return None


def _straight_push(state: SceneState, start: tuple[float, float],
                   end: tuple[float, float]) -> bool:
    """No wall between `start` and `end` (sampled every PUSH_STEP metres)."""
    steps = max(1, math.ceil(math.dist(start, end) / PUSH_STEP))
    return all(state.sim.cube_fits(start[0] + (end[0] - start[0]) * k / steps,
                                   start[1] + (end[1] - start[1]) * k / steps, [], 0.0)
               for k in range(1, steps + 1))
