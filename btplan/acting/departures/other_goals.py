"""Keep the other goals in view when choosing and placing achievers (`credit_other_goals`).

Achievers whose effects make other goals true are ranked first
(btplan.acting.departures.credit), and before an achiever runs, the rest of a step of
another goal that it enables is set up (btplan.acting.departures.prepare). The
conditions added that way are optional: one that finds no achiever or no place is
given up, not counted as stuck.
"""

from __future__ import annotations

from btplan.acting.departures.credit import credit_goals
from btplan.acting.departures.prepare import (
    RelaxedPlans,
    give_up,
    prepare_before,
    relaxed_plans,
)
from btplan.acting.hooks import Departure
from btplan.bt import Fallback, Node
from btplan.model import Atom, GroundAction, GroundLiteral


class OtherGoals(Departure):
    """Credit and preparation for the other goals; keeps the conditions it added."""

    name = "credit_other_goals"

    def __init__(self) -> None:
        self.added: set[Node] = set()
        """Conditions added before an achiever for another goal's step."""
        self._plans: RelaxedPlans | None = None

    def rank_achievers(self, achievers: list[GroundAction], literal: GroundLiteral,
                       state: frozenset[Atom]) -> list[GroundAction]:
        """The `rank_achievers` hook: achievers that also make other open goals true come first
        (`credit_goals`), before the width cuts the list."""
        loop = self.loop
        return credit_goals(achievers, literal, loop.task.goal_literals, loop.index.relaxed,
                            state)

    def new_subtree(self, subtree: Fallback, achievers: list[GroundAction],
                    literal: GroundLiteral, state: frozenset[Atom]) -> None:
        """The `new_subtree` hook: add before the first achiever the conditions of another goal's
        step it enables (`prepare_before`), remember them as optional and queue them to expand."""
        if self._plans is None:
            self._plans = relaxed_plans(self.loop.index.relaxed)
        wanted = prepare_before(self.loop, subtree, achievers[0], literal, state, self.added,
                                self._plans)
        self.added.update(wanted)
        self.loop.early.extend(wanted)

    def optional(self, node: Node) -> bool:
        """The `optional` hook: the conditions this departure added are extras, never needs."""
        return node in self.added

    def gives_up(self, node: Node) -> bool:
        """The `gives_up` hook: a stuck condition this departure added is taken out of the tree
        (`give_up`) rather than counted as stuck; False for every other condition."""
        return node in self.added and give_up(node)
