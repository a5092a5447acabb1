"""Acting configurations the tests name, beside the presets of btplan.acting.config.

Many tests count ticks and expansions as Algorithm 1's loop makes them (one expansion
per tick, no departure) with btplan's own ranking of achievers; others switch single
departures on to show what each one does.
"""

from __future__ import annotations

from btplan.acting.config import ACTING_PLANNER, ActingConfig
from btplan.planner import PlannerOptions

ALGORITHM_1 = ActingConfig.algorithm1()
"""Algorithm 1's loop, with btplan's planner options for the expansions."""


def departures(planner: PlannerOptions = ACTING_PLANNER, *, look_ahead: bool = False,
               look_deeper: bool = False, scope_moves: bool = False,
               goal_credit: bool = False, finish_first: bool = False) -> ActingConfig:
    """Algorithm 1's loop with the named departures on; `planner.expansions_per_tick`
    is the tick's expansion budget."""
    return ActingConfig.paper(
        name="departures", planner=planner, expansions_per_tick=planner.expansions_per_tick,
        expand_later_preconditions=look_ahead, expand_when_forced=look_deeper,
        skip_moved_while_held=scope_moves, credit_other_goals=goal_credit,
        finish_halted_action=finish_first)
