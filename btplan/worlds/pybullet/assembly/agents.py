"""The assembly scene's external agents: someone turns a part over, or knocks it away.

Each `[[event]]` of the scene fires once, at a tick or `delay` ticks after the `count`-th
time its `when` literal became true (watched through the world's own `check`). The
part is lifted out of wherever it is (a gripper lets go of it) and laid in the event's
place: turned over for `flip`, as it was for `knock`. A place below the table (the
floor) drops it there.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from btplan.errors import InputError, Span
from btplan.worlds.agents import Disturbance
from btplan.worlds.pybullet.assembly.scene import Event
from btplan.worlds.pybullet.assembly.state import AssemblyState

Check = Callable[[tuple[str, tuple[str, ...]]], bool]


def literal(text: str, path: str) -> tuple[bool, str, tuple[str, ...]]:
    """`mounted(chassis)` or `not free(left)` as (positive, predicate, args)."""
    body = text.strip()
    positive = not body.startswith("not ")
    name, _, rest = body.removeprefix("not ").strip().partition("(")
    if not name.isidentifier() or (rest and not rest.endswith(")")):
        raise InputError(f"cannot read the condition {text!r}", Span(path, 1, 1),
                         "write it as in the domain, e.g. mounted(chassis)")
    args = tuple(a.strip() for a in rest[:-1].split(",") if a.strip()) if rest else ()
    return positive, name, args


@dataclass(slots=True)
class Watch:
    """One event and its progress."""

    event: Event
    when: tuple[bool, str, tuple[str, ...]] | None
    seen: int = 0
    was: bool = False
    due: int | None = None
    done: bool = False

    def ready(self, check: Check, tick: int) -> bool:
        """Whether the event fires at `tick`; never again once it is done.

        It is due at its tick, or `delay` ticks after its `when` literal became true for the
        `count`-th time (changes from false to true are counted, not ticks spent true).
        """
        if self.done:
            return False
        if self.due is None and self.event.tick is not None:
            self.due = self.event.tick
        if self.due is None and self.when is not None:
            positive, name, args = self.when
            now = check((name, args)) is positive
            self.seen += int(now and not self.was)
            self.was = now
            if self.seen >= self.event.count:
                self.due = tick + self.event.delay
        return self.due is not None and tick >= self.due


@dataclass(slots=True)
class AssemblyAgents:
    """All events of the scene, acting as one external agent before each tick."""

    state: AssemblyState
    check: Check
    watches: list[Watch] = field(default_factory=list)
    name: str = "scene"

    def act(self, world: object, tick: int) -> list[Disturbance]:
        """Fire every event due at `tick`, each only once.

        `world` is not used: the agent was built on the scene state and the world's `check`.
        """
        happened = []
        for watch in self.watches:
            if watch.ready(self.check, tick):
                watch.done = True
                happened.append(Disturbance(tick, self.name, self.apply(watch.event), "scene"))
        return happened

    def apply(self, event: Event) -> str:
        """Lay the event's part in its place: turned over for `flip`, as it faces for `knock`.

        A place below the table takes it at its centre, on the floor; a table place needs a
        free spot, or nothing happens. A grip on the part is let go. Returns what happened.
        """
        state = self.state
        face = state.face(event.part) or "up"
        if event.do == "flip":
            face = "down" if face == "up" else "up"
        place = state.place(event.to)
        spot = place.center if place.below else state.free_spot(event.to, event.part)
        if spot is None:
            return f"{event.name}: no room for {event.part} in {event.to}"
        state.lay(event.part, spot, face, place.below)
        verb = "turns over" if event.do == "flip" else "knocks"
        return f"{event.name}: {verb} {event.part}, now in {event.to} opening {face}"


def assembly_agents(state: AssemblyState, check: Check) -> AssemblyAgents:
    """The scene's events as one agent, watching `when` literals through `check`.

    A literal that cannot be read is an InputError naming the scene file.
    """
    events = state.scene.events
    watches = [Watch(e, literal(e.when, state.scene.path) if e.when else None) for e in events]
    return AssemblyAgents(state, check, watches)
