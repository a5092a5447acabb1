"""Guards before each new achiever that keep the other goals reachable (`protect_goals`).

An option of the planner, off by default: the white knights of btplan.planner.protect
become conditions at the head of each alternative of a new atomic BT.
"""

from __future__ import annotations

from btplan.acting.hooks import Departure
from btplan.acting.state import LoopState
from btplan.bt import Action, Composite, Fallback
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.expand import condition_node


def protect(loop: LoopState, subtree: Fallback) -> None:
    """Check, before each new achiever, what keeps the other goals reachable."""
    from btplan.planner.protect import white_knights  # an option, off by default

    state = loop.world.facts()
    for alternative in subtree.children[1:]:
        last = alternative.children[-1] if alternative.children else None
        if not isinstance(last, Action) or last.key not in loop.grounding:
            continue
        action = loop.grounding[last.key]
        for atom in white_knights(action, state, loop.task.goal_literals,
                                  loop.index.relaxed):
            guard = condition_node(GroundLiteral(atom, True), loop.task)
            assert isinstance(alternative, Composite)
            alternative.insert(0, guard)


class ProtectGoals(Departure):
    """The `protect_goals` option of the planner, at the new subtree."""

    name = "protect_goals"

    def new_subtree(self, subtree: Fallback, achievers: list[GroundAction],
                    literal: GroundLiteral, state: frozenset[Atom]) -> None:
        """The `new_subtree` hook: guard each new alternative with the white knights that keep
        the other goals reachable (`protect`), before IncreasePriority places the subtree."""
        protect(self.loop, subtree)
