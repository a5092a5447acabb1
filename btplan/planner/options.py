"""The knobs of the planner, with defaults that work on the shipped domains."""

from __future__ import annotations

from btplan.records import record, replace

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any


@record(frozen=True, slots=True)
class PlannerOptions:
    """Bounds and strategy switches for backchaining.

    `max_alternatives` bounds the fallback width of one atomic BT (the paper keeps
    every achiever; real domains have too many groundings). `max_bindings` bounds the
    groundings enumerated per action template before ranking. `heuristic` ranks
    achievers by a relaxed-reachability estimate (h_add) instead of the first match.
    `reorder_goals` lets conflict resolution move an enclosing subtree when moving
    the new subtree alone, as the paper does, finds no conflict-free place. `mutexes`
    judges conflicts by h^2 mutual exclusion rather than by single effects.
    `refine_more` prunes circular and conflicting achievers and lets a failed,
    expanded condition gain achievers that fit a later state. `protect_goals` adds,
    before an achiever that would make a goal unreachable, a condition that keeps it
    reachable (costly: plan() uses it as its last fallback). `closest_first` expands the
    failed condition nearest to the state (h_add) instead of the first in breadth-first
    order; `avoid_dead_ends` drops achievers that would make a condition the enclosing
    sequences still need unreachable (btplan/planner/lookahead.py). `prune_bindings`
    skips bindings with a precondition unreachable from the state while enumerating,
    so `max_bindings` counts only bindings that could run. `backtrack` tries the
    next-ranked achievers when the chosen ones have no conflict-free place.
    `retries` starts a failed attempt over that many times, each time without one more
    achiever choice the failure is blamed on (btplan/planner/backjump.py).
    `search_stuck`, the last resort, plans a stuck condition by a complete search
    (btplan/classical/search.py) and inserts the plan as a subtree. `goal_agenda` orders
    the goals by reasonable orders before the tree is built (btplan/planner/agenda.py);
    `state_agenda` adds the orders the initial state imposes (`agenda.state_orders`;
    plan() turns it on in a fallback strategy).
    `expansions_per_tick` lets the acting loop tick the tree again, within the same tick
    (the world has not moved), after an expansion, up to that many expansions: Algorithm 1
    as published spends a tick of the world per expansion, which a sequential planner,
    planning before it acts, does not. `improve_plan`: offline planning shortens the
    executed plan once found (btplan/classical/improvement.py) and puts the shorter plan
    ahead of the tree (btplan/acting/offline/improved.py). `PlannerOptions.paper()` turns every
    departure from the paper off, for comparison.
    """

    max_expansions: int = 1000
    max_alternatives: int = 4
    max_bindings: int = 64
    heuristic: bool = True
    reorder_goals: bool = True
    mutexes: bool = True
    refine_more: bool = True
    protect_goals: bool = False
    closest_first: bool = True
    avoid_dead_ends: bool = True
    prune_bindings: bool = True
    backtrack: bool = True
    retries: int = 6
    search_stuck: bool = True
    goal_agenda: bool = True
    state_agenda: bool = False
    stall_limit: int = 3
    expansions_per_tick: int = 1
    improve_plan: bool = True

    @classmethod
    def paper(cls, **changes: Any) -> PlannerOptions:
        """Algorithms 1-3 as published: first-match order, no extensions."""
        base = cls(heuristic=False, reorder_goals=False, mutexes=False, refine_more=False,
                   closest_first=False, avoid_dead_ends=False, prune_bindings=False,
                   backtrack=False, retries=0, search_stuck=False,
                   goal_agenda=False, improve_plan=False)
        return replace(base, **changes)
