"""Which departures a loop runs with: from its ActingConfig and its planner options.

The order is the order of the hooks' calls: at a new subtree, the step of another goal
is prepared first, then the goals are protected, then the subtree's place is noted for
scoping, as the measurements in docs/results/reactivity.md were made.
"""

from __future__ import annotations

from btplan.acting.config import ActingConfig
from btplan.acting.hooks import Departure
from btplan.planner import PlannerOptions


def departures_for(config: ActingConfig, options: PlannerOptions) -> list[Departure]:
    """The departures `config` (and the planner's `options`) switch on, in hook order."""
    from btplan.acting.departures.finishing import FinishHalted
    from btplan.acting.departures.forced import ForcedFirst
    from btplan.acting.departures.later import LaterPreconditions
    from btplan.acting.departures.other_goals import OtherGoals
    from btplan.acting.departures.protect import ProtectGoals
    from btplan.acting.departures.regrow import Regrow
    from btplan.acting.departures.scoped import ScopedMoves
    from btplan.acting.departures.search import LastResortSearch

    chosen: list[Departure] = []
    if config.expand_later_preconditions:
        chosen.append(LaterPreconditions())
    elif config.expand_when_forced:
        chosen.append(ForcedFirst())
    if config.credit_other_goals:
        chosen.append(OtherGoals())
    if options.protect_goals:
        chosen.append(ProtectGoals())
    if config.skip_moved_while_held:
        chosen.append(ScopedMoves())
    if config.finish_halted_action:
        chosen.append(FinishHalted())
    if options.refine_more:
        chosen.append(Regrow())
    if options.search_stuck:
        chosen.append(LastResortSearch())
    return chosen
