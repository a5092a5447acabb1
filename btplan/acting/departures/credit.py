"""Achievers that also make a goal true come first, and are pursued as such.

Backchaining ranks the achievers of a condition by what their own preconditions cost
from the state of now (btplan.planner.achievers), one condition at a time. In
blocksworld, to empty the hand that holds b4, `put_down(b4)` is the cheapest; but b4's
goal is `on(b4, b5)`, so the block goes down to the table and is picked up again later,
two actions a plan does not make. Here an achiever that can run now is credited with
the h_add cost of the goals still false that its effects make true (`stack(b4, b5)`
makes `on(b4, b5)`), so its rank is what it costs less what it saves on the rest of
the goal.

Ranking it first is not enough: a Fallback runs the first alternative that can run,
so while b5 is covered `put_down(b4)` would still run. That b5 is cleared before b4
is taken off b3 is btplan.acting.departures.prepare's part; with both, `stack(b4, b5)` runs when
b4 is in hand. Off in the published algorithm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.classical import RelaxedModel


def credit_goals(
    achievers: Sequence[GroundAction], condition: GroundLiteral,
    goals: Sequence[GroundLiteral], relaxed: RelaxedModel, state: frozenset[Atom],
) -> list[GroundAction]:
    """`achievers` (ranked) ranked again by cost plus h_add of their false preconditions,
    less, for those that can run now, the h_add of the goals still false that they make
    true; ties keep the order. Unchanged when none makes such a goal true.

    Only an achiever that can run now is credited: the h_add of false preconditions may
    count on the very condition being achieved (`stack(b3, b1)` makes `clear(b3)`, but
    holding b3 needs b3 clear first), which would make a circular achiever look cheap."""
    open_goals = [g.atom for g in goals
                  if g.positive and g != condition and not g.holds(state)]
    if len(achievers) < 2 or not open_goals:
        return list(achievers)
    if not any(g in a.add for a in achievers for g in open_goals):
        return list(achievers)
    cost = relaxed.costs(state)

    def score(item: tuple[int, GroundAction]) -> tuple[float, int]:
        rank, action = item
        missing = sum(cost.get(p.atom, math.inf) for p in action.preconditions
                      if p.positive and p.atom not in state)
        if missing:  # the h_add of its preconditions may count on the condition itself
            return action.cost + missing, rank
        saved = sum(cost.get(g, 0.0) for g in open_goals if g in action.add)
        return action.cost - saved, rank

    return [a for _, a in sorted(enumerate(achievers), key=score)]
