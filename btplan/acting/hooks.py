"""The named hooks of the blended loop, where each departure from Algorithm 1 plugs in.

The loop (btplan.acting.loop) is Algorithm 1: tick, GetConditionToExpand, ExpandTree,
IncreasePriority. Everything btplan does beyond it is a `Departure`: an object with
its own state that the loop calls at these points, in the order the departures were
given. A departure changes the loop only through the loop's own methods (`LoopState`
in btplan.acting.state): it schedules early expansions, marks conditions never to
expand, grounds actions; it never writes the loop's fields.

Hooks, in the order a tick meets them:

- `before_tick(report, last)`: the world changed since the last tick (`last` is the
  state after it); the watch on the way ahead expands what an outside change broke.
- `world_for_tick(world)`: the world the tree ticks against this tick (finishing a
  halted action first wraps it); `end_tick()` after the tick.
- `rank_achievers(achievers, literal, state)`: reorder the achievers of a condition
  before the width is cut (credit for other goals).
- `before_expansion(node, state)`: `node` was chosen and is about to be replaced by
  its atomic BT (the look-ahead notes the later false preconditions next to it).
- `new_subtree(subtree, achievers, literal, state)`: ExpandTree made `subtree`,
  before IncreasePriority moves it.
- `placed(subtree, moves)`: IncreasePriority put it where nothing conflicts.
- `after_expansion(report)`: within the same tick, before the grown tree is ticked.
- `expand_again(state)`: nothing new to expand; an expanded condition may gain
  achievers that fit the state now (refinement depends on the state).
- `when_stuck(node)`: no achiever or no conflict-free place for `node`; a departure
  may grow the tree another way (the last-resort search).
- `gives_up(node)`: whether a condition a departure added may be dropped instead of
  counting as stuck; `optional(node)`: whether it is such a condition.
- `new_world(world)`: the loop goes on against another world (offline rounds).
"""

from __future__ import annotations

from collections.abc import Sequence

from btplan.acting.state import Expansion, LoopState, TickReport
from btplan.bt import Fallback, Node, World
from btplan.model import Atom, GroundAction, GroundLiteral

__all__ = ["Departure", "Hooks"]


class Departure:
    """A departure from Algorithm 1: override the hooks it needs (module docstring)."""

    name = "departure"

    def attach(self, loop: LoopState) -> None:
        """Called once, when the loop is made."""
        self.loop = loop

    def before_tick(self, report: TickReport, last: frozenset[Atom]) -> None:
        """The world changed since the tick that left it in `last`."""

    def world_for_tick(self, world: World) -> World:
        """The world the tree ticks against this tick (by default `world` itself)."""
        return world

    def end_tick(self) -> None:
        """The tick is over."""

    def rank_achievers(self, achievers: list[GroundAction], literal: GroundLiteral,
                       state: frozenset[Atom]) -> list[GroundAction]:
        """The achievers of `literal`, reordered before the width is cut (by default
        as they came)."""
        return achievers

    def before_expansion(self, node: Node, state: frozenset[Atom]) -> None:
        """`node` is about to be expanded."""

    def new_subtree(self, subtree: Fallback, achievers: list[GroundAction],
                    literal: GroundLiteral, state: frozenset[Atom]) -> None:
        """ExpandTree made `subtree`; IncreasePriority has not moved it yet."""

    def placed(self, subtree: Fallback, moves: int) -> None:
        """IncreasePriority placed `subtree` after `moves` moves."""

    def after_expansion(self, report: TickReport) -> None:
        """An expansion was made in this tick."""

    def expand_again(self, state: frozenset[Atom]) -> Expansion | None:
        """Nothing new to expand: an expansion this departure makes instead, or None."""
        return None

    def when_stuck(self, node: Node) -> Expansion | None:
        """`node` has no achiever or no conflict-free place: an expansion this departure
        makes another way, or None."""
        return None

    def optional(self, node: Node) -> bool:
        """Whether `node` is a condition this departure added, which may be dropped."""
        return False

    def gives_up(self, node: Node) -> bool:
        """Whether this departure drops the stuck condition `node` instead of the run
        counting it as stuck."""
        return False

    def new_world(self, world: World) -> None:
        """The loop goes on against another world."""


class Hooks:
    """The departures of one loop, called in order at each hook."""

    def __init__(self, departures: Sequence[Departure]) -> None:
        self.departures = tuple(departures)
        # Only the departures that override a hook are called at it: the hooks run
        # on every tick and every expansion.
        self._at = {name: tuple(d for d in self.departures
                                if getattr(type(d), name) is not getattr(Departure, name))
                    for name in ("before_tick", "world_for_tick", "end_tick",
                                 "rank_achievers", "before_expansion", "new_subtree",
                                 "placed", "after_expansion", "expand_again", "when_stuck",
                                 "optional", "gives_up", "new_world")}

    def attach(self, loop: LoopState) -> None:
        """Give every departure the loop, once."""
        for departure in self.departures:
            departure.attach(loop)

    def before_tick(self, report: TickReport, last: frozenset[Atom]) -> None:
        """Each departure that watches for outside changes, in order."""
        for d in self._at["before_tick"]:
            d.before_tick(report, last)

    def world_for_tick(self, world: World) -> World:
        """The world wrapped by each departure in turn."""
        for d in self._at["world_for_tick"]:
            world = d.world_for_tick(world)
        return world

    def end_tick(self) -> None:
        """Tell each departure the tick is over."""
        for d in self._at["end_tick"]:
            d.end_tick()

    def rank_achievers(self, achievers: list[GroundAction], literal: GroundLiteral,
                       state: frozenset[Atom]) -> list[GroundAction]:
        """The achievers as each departure reorders them, in turn."""
        for d in self._at["rank_achievers"]:
            achievers = d.rank_achievers(achievers, literal, state)
        return achievers

    def before_expansion(self, node: Node, state: frozenset[Atom]) -> None:
        """Tell each departure which condition is about to be expanded."""
        for d in self._at["before_expansion"]:
            d.before_expansion(node, state)

    def new_subtree(self, subtree: Fallback, achievers: list[GroundAction],
                    literal: GroundLiteral, state: frozenset[Atom]) -> None:
        """Tell each departure of the subtree ExpandTree made."""
        for d in self._at["new_subtree"]:
            d.new_subtree(subtree, achievers, literal, state)

    def placed(self, subtree: Fallback, moves: int) -> None:
        """Tell each departure where IncreasePriority put the subtree."""
        for d in self._at["placed"]:
            d.placed(subtree, moves)

    def after_expansion(self, report: TickReport) -> None:
        """Tell each departure an expansion was made in this tick."""
        for d in self._at["after_expansion"]:
            d.after_expansion(report)

    def expand_again(self, state: frozenset[Atom]) -> Expansion | None:
        """The first expansion a departure makes when nothing new was expanded."""
        for d in self._at["expand_again"]:
            found = d.expand_again(state)
            if found is not None:
                return found
        return None

    def when_stuck(self, node: Node) -> Expansion | None:
        """The first expansion a departure makes for a stuck condition."""
        for d in self._at["when_stuck"]:
            found = d.when_stuck(node)
            if found is not None:
                return found
        return None

    def optional(self, node: Node) -> bool:
        """Whether any departure added this condition as one that may be dropped."""
        return any(d.optional(node) for d in self._at["optional"])

    def gives_up(self, node: Node) -> bool:
        """Whether any departure drops this stuck condition."""
        return any(d.gives_up(node) for d in self._at["gives_up"])

    def new_world(self, world: World) -> None:
        """Tell each departure the loop goes on against another world."""
        for d in self._at["new_world"]:
            d.new_world(world)
