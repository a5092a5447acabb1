"""btplan's extensions of Algorithm 1, as one setting: the method docs/reactivity.md measures.

`btplan sweep --method btplan` and `btplan run --extended` run the loop with these, so
that what a user runs is what the benchmarks measured. Each extension is an option of
`acting.run` (its docstring says what each does); which ones are on depends on the
world:

- Look-ahead (and the watch on the way ahead) refines later actions before the robot
  moves; in the simulator their trajectories would start from where the robot stands
  now, and go stale before they are driven, so there it is off. The deeper look alone
  refines nothing ahead: it expands a later condition early only when its achiever
  would make the robot give up what it is about to hold (on `shove`, it clears the
  doorway before green is picked up).
- Goal credit was measured on the symbolic scenarios only, so the simulator goes
  without it.
- Scoped moves and finishing a halted action first count in both. On `shove`, a Pick
  whose cube once blocked the path ahead is halted by that path's check as the fingers
  close, and started again by the branch that puts the cube aside; without finishing it
  first, the pick starts over every time and the run goes round.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TypedDict

from btplan.acting.online import ACTING_OPTIONS
from btplan.planner import PlannerOptions

EXPANSIONS = 64
"""Expansions the loop may make within one tick before the world moves on (a sequential
planner too plans and starts acting in the same tick); Algorithm 1 as published makes one."""


def extended_options(stall_limit: int | None = None) -> PlannerOptions:
    """The planner's acting options with up to EXPANSIONS expansions per tick (and the
    loop's stall limit, when given: the sweep gives every method its whole budget)."""
    options = replace(ACTING_OPTIONS, expansions_per_tick=EXPANSIONS)
    return options if stall_limit is None else replace(options, stall_limit=stall_limit)


class Extensions(TypedDict):
    """The keyword options of `acting.run` that switch an extension on or off."""

    look_ahead: bool
    look_deeper: bool
    scope_moves: bool
    goal_credit: bool
    finish_first: bool


def extensions(simulated: bool) -> Extensions:
    """The extensions the extended method turns on, in the symbolic world or
    (`simulated`) in one whose actions refine values as they run."""
    return Extensions(look_ahead=not simulated, look_deeper=True, scope_moves=True,
                      goal_credit=not simulated, finish_first=True)


NONE = Extensions(look_ahead=False, look_deeper=False, scope_moves=False, goal_credit=False,
                  finish_first=False)
"""Algorithm 1 with none of them (`acting.run`'s defaults)."""
