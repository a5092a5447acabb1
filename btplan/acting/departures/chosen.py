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
    """The departures `config` (and the planner's `options`) switch on, in hook order.

    Each is imported only when switched on: offline planning runs two of them, and the
    first call of a `btplan plan` process counted the others' imports (about 3 ms)."""
    chosen: list[Departure] = []
    if config.expand_later_preconditions:
        from btplan.acting.departures.later import LaterPreconditions

        chosen.append(LaterPreconditions())
    elif config.expand_when_forced:
        from btplan.acting.departures.forced import ForcedFirst

        chosen.append(ForcedFirst())
    if config.credit_other_goals:
        from btplan.acting.departures.other_goals import OtherGoals

        chosen.append(OtherGoals())
    if options.protect_goals:
        from btplan.acting.departures.protect import ProtectGoals

        chosen.append(ProtectGoals())
    if config.skip_moved_while_held:
        from btplan.acting.departures.scoped import ScopedMoves

        chosen.append(ScopedMoves())
    if config.finish_halted_action:
        from btplan.acting.departures.finishing import FinishHalted

        chosen.append(FinishHalted())
    if config.leave_plan_once_departed and (config.plan_before_acting
                                            or config.plan_offline_when_stuck):
        from btplan.acting.departures.leave_plan import LeavePlan

        chosen.append(LeavePlan())
    if options.refine_more:
        from btplan.acting.departures.regrow import Regrow

        chosen.append(Regrow())
    if options.search_stuck:
        from btplan.acting.departures.search import LastResortSearch

        chosen.append(LastResortSearch())
    return chosen
