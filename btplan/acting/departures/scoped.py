"""Skip a moved subtree while what it was moved for holds (`skip_moved_while_held`).

btplan.acting.departures.scope says why and how; this is its place in the loop: the
new subtree's lineage is noted before IncreasePriority moves it, and the conditions
that scope it are added once it has moved.
"""

from __future__ import annotations

from btplan.acting.departures.scope import lineage, scope_moved
from btplan.acting.hooks import Departure
from btplan.bt import Fallback, Node
from btplan.model import Atom, GroundAction, GroundLiteral


class ScopedMoves(Departure):
    """Remembers where a new subtree stood, and scopes it if it moved."""

    name = "skip_moved_while_held"

    def __init__(self) -> None:
        self.before: list[Node] = []

    def new_subtree(self, subtree: Fallback, achievers: list[GroundAction],
                    literal: GroundLiteral, state: frozenset[Atom]) -> None:
        """The `new_subtree` hook: remember the subtree's lineage before IncreasePriority moves
        it, the only way to know later which Fallbacks it left."""
        self.before = lineage(subtree)

    def placed(self, subtree: Fallback, moves: int) -> None:
        """The `placed` hook: if the subtree moved, make it skip while a condition it was moved
        away from holds (`scope_moved`); those guards are never expanded."""
        before, self.before = self.before, []
        if moves and before:
            self.loop.never_expand(scope_moved(before, self.loop.task))
