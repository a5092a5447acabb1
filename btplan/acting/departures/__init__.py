"""The departures from Algorithm 1, each an object behind the hooks of btplan.acting.hooks.

- `later.LaterPreconditions`: expand an action's later false preconditions with its
  first, and what an outside change breaks ahead of the running action (`ahead`,
  `watch` hold the tree walks).
- `forced.ForcedFirst`: without the look-ahead, expand a later precondition early only
  when it forces the order.
- `other_goals.OtherGoals`: credit achievers for the other goals they make true
  (`credit`), and set up the step of another goal an achiever enables (`prepare`).
- `scoped.ScopedMoves`: skip a moved subtree while what it was moved for holds (`scope`).
- `finishing.FinishHalted`: finish a halted action first when nothing is lost (`finish`).
- `protect.ProtectGoals`, `regrow.Regrow`, `search.LastResortSearch`: the planner's
  `protect_goals`, `refine_more` and `search_stuck` options while acting
  (`refined_search` for worlds that refine values).
- `leave_plan.LeavePlan`: act on the backchained tree alone once the world departs
  from the plan that planning before acting put first.
- `chosen.departures_for`: which of them a configuration switches on.
"""

from __future__ import annotations

from btplan.acting.departures.chosen import departures_for

__all__ = ["departures_for"]
