"""Expand a later false precondition early only when it forces the order
(`expand_when_forced`, without the look-ahead).

A later precondition whose achiever needs something that would make the robot give
up what it is about to hold (the doorway to clear needs an empty hand, and the cube
is about to fill it) must be expanded before the robot takes the cube, or the tree
finds it only with the cube in hand. The others wait for the tick, as in Algorithm 1.
"""

from __future__ import annotations

from btplan.acting.departures.ahead import later_false
from btplan.acting.hooks import Departure
from btplan.acting.state import TickReport
from btplan.bt import Node
from btplan.model import Atom


class ForcedFirst(Departure):
    """Keeps the later false preconditions of the condition being expanded, and expands
    those that force the order once the expansion is made (module docstring)."""

    name = "expand_when_forced"

    def __init__(self) -> None:
        self.later: list[Node] = []

    def before_expansion(self, node: Node, state: frozenset[Atom]) -> None:
        """The `before_expansion` hook: note `node`'s later false siblings now, while `node` still
        stands in its Sequence; ExpandTree is about to move it under a Fallback."""
        self.later = later_false(node, state, self.loop.expanded)

    def after_expansion(self, report: TickReport) -> None:
        """The `after_expansion` hook: of the noted conditions, expand at once only those that
        force the order (`EarlyExpansions.expand_if_forced`); the others wait for their tick."""
        later, self.later = self.later, []
        self.loop.early.expand_if_forced(report, later)
