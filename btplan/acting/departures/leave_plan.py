"""Leave the offline plan once the world departs from it.

Planning before acting (btplan.acting.offline_turns) hands the loop a tree that runs
the shorter plan first: a Fallback of the plan's steps, latest first, ahead of the
backchained tree (btplan.planner.plan_first). While the world follows the plan,
some step's condition holds and the tree executes the plan. Once no step fits, the
backchained tree acts, and the loop grows it. From then on the steps are a second
strategy competing with the first: each time an outside change makes some step's
condition hold again, the tree turns back to the plan, halts what the backchained tree
started, and the two take turns. Measured on the reactivity sweep's `towers` at
p = 0.3 (30 seeds): 69 ticks to the goal with the steps kept, 17.5 with them left.

So the first tick in which the backchained part runs, or the tree fails and grows,
ends the plan: the loop acts on the backchained tree alone (`LoopState.narrow_to`).
An undisturbed run never gets there, and executes the plan as before.
"""

from __future__ import annotations

from btplan.acting.hooks import Departure
from btplan.acting.state import TickReport
from btplan.bt import IDLE
from btplan.planner.plan_first import backchained_part

__all__ = ["LeavePlan"]


class LeavePlan(Departure):
    """Drops the plan's steps from the tree at the first tick that departs from them."""

    name = "leave plan"

    def __init__(self) -> None:
        self.grown = False

    def after_expansion(self, report: TickReport) -> None:
        """The tree failed and grew: no step of the plan fitted."""
        self.grown = True

    def end_tick(self) -> None:
        """Narrow the loop to the backchained tree once it ran, or the tree grew."""
        grown, self.grown = self.grown, False
        part = backchained_part(self.loop.tree.root)
        if part is not None and (grown or part.status is not IDLE):
            self.loop.narrow_to(part)
