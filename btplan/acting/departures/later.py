"""Expand an action's later false preconditions with its first, and what an outside change
breaks ahead of the running action (`expand_later_preconditions`).

A Sequence stops at its first failing child, so Algorithm 1 expands an action's
preconditions one tick at a time, and the robot starts the first achiever before it
knows that a later precondition needs a step that conflicts with it. Here the later
false preconditions are expanded in the same tick (btplan.acting.early), and before
each tick the conditions ahead of the running actions that held after the last tick
and no longer hold are expanded at once (btplan.acting.departures.watch), not when the
robot gets there.
"""

from __future__ import annotations

from btplan.acting.departures.ahead import later_false
from btplan.acting.hooks import Departure
from btplan.acting.state import TickReport
from btplan.bt import Node
from btplan.model import Atom


class LaterPreconditions(Departure):
    """The look-ahead and the watch on the way ahead (module docstring)."""

    name = "expand_later_preconditions"

    def before_tick(self, report: TickReport, last: frozenset[Atom]) -> None:
        """The `before_tick` hook: expand what an outside change broke ahead of the running
        actions since `last`, instead of when the robot gets there."""
        self.loop.early.expand_broken(report, last)

    def before_expansion(self, node: Node, state: frozenset[Atom]) -> None:
        """The `before_expansion` hook: queue all of `node`'s later false siblings to expand in
        this tick, replacing what the previous expansion queued."""
        # Looked up before ExpandTree moves the node under a Fallback.
        self.loop.early.replace(later_false(node, state, self.loop.expanded))
