"""Shorter plans once a plan is found: action elimination, then plan-neighbourhood search.

Backchaining achieves one condition at a time with the achiever it ranked best in the
state it expanded in, so its executed plan can hold steps that later work made
useless (a truck driven somewhere and back) and detours a planner that looked at the
whole plan would not take. Nothing in the tree shortens them. Offline planning
therefore post-processes the executed plan, as the Aras optimiser does (Nakhost and
Müller, "Action Elimination and Plan Neighborhood Graph Search: Two Algorithms for
Plan Improvement", ICAPS 2010):

* Action elimination: remove one step, and every later step that can no longer run;
  keep the removal when the goal still holds at the end. Each step is tried once, first
  to last, on the shortened plan.
* Plan-neighbourhood graph search: the states within `depth` steps of the plan's
  trajectory (breadth first, bounded by a number of states), then the cheapest path
  from the initial state to a goal state within them. A better plan is eliminated
  again and becomes the new trajectory; otherwise the neighbourhood grows one step,
  until the time or the state budget runs out, the neighbourhood has grown far past
  the one that last found a better plan (PATIENCE), or no new state is left to reach
  (the path found is then the best there is).

Both work on the grounded actions packed as bit masks (btplan/classical/packed.py); the
neighbourhoods are btplan/classical/neighbourhood.py's.
A plan is better when it costs less, or costs the same and has fewer steps. Plans with
an action the packed actions do not hold (deletes by pattern) are left as they are.
"""

from __future__ import annotations

from collections.abc import Sequence

from btplan.model import GroundAction
from btplan.classical.neighbourhood import Limits, Neighbourhood, OutOfTime, PlanSpace
from btplan.records import record

PATIENCE = 10
"""The search gives up once a neighbourhood holds this many times the states of the
one that last made the plan better (or of the plan's trajectory), and at least
PATIENCE_STATES, without a better plan. Each step further out multiplies the states by
about the branching; on the training domains' small problems a better plan came one
step beyond a neighbourhood that found none (zenotravel p01: 2,000 states, then 24,000),
and mystery p01, whose neighbourhood holds every reachable state only at 131,000 states
and finds nothing, stops early instead of running into the time budget. With 500 at
least, the 15 training problems pyperplan also solves get the same plans as with 2,000,
and the search's cost on the small ones, which decide the median run time, falls from
20-35 ms to 8-19 ms (mystery p01, pipesworld p01 and p03)."""

PATIENCE_STATES = 500

PATIENCE_PER_STEP = 100
"""...and at least this many states per step of the plan: a longer plan has more places to
regroup, further apart. Generated logistics (4 to 12 packages, 15-64 steps): median plan
length 1.29 times pyperplan's with 500 states alone, 1.00 with this; gripper 1.09 and
0.90 (bench/planning.py --domains gripper,logistics --seeds 1)."""

PATIENCE_PER_STEP_MAX = 10_000
"""...but for at most this many states: visit-all's 242-450-step plans let neighbourhoods
that never found a shorter plan grow to 44,000-50,000 states (10 MB, a third of the
process); with this bound they stop at 12,000-23,000, and every training problem keeps
the plan it had."""


SLACK_STATES = 250
"""...but, where a lower bound on the steps of any plan is known (bound.py), at most
this many states per step the plan is above it: a plan one step above the bound can
lose one step at most, and the neighbourhoods that look for it grow by the branching
with each step out (pipesworld p01 and p03, one above: 1,082 and 1,844 states, 16 and
12 ms, where 250 stops at 271 and 255)."""


@record
class Improvement:
    """A shorter plan and where its savings came from."""

    steps: list[GroundAction]
    before: int
    """Steps of the plan given."""
    eliminated: int = 0
    """Steps removed by action elimination."""
    searched: int = 0
    """Steps saved by the plan-neighbourhood search (beyond its eliminations)."""
    depth: int = 0
    """The widest neighbourhood looked at, in steps from the trajectory."""
    states: int = 0
    """States the largest neighbourhood held."""
    complete: bool = False
    """Whether the last neighbourhood held every state reachable from the trajectory, so
    no cheaper plan exists at all."""

    def looked_at(self, depth: int, states: int, complete: bool) -> None:
        """A neighbourhood was searched: keep the widest and largest, and the last's
        completeness (only the last one speaks for the plan returned)."""
        self.depth = max(self.depth, depth)
        self.states = max(self.states, states)
        self.complete = complete

    def shortened(self, searched: int, eliminated: int) -> None:
        """The search found a cheaper plan, `searched` steps shorter, and eliminating
        after it removed `eliminated` more."""
        self.searched += searched
        self.eliminated += eliminated


def eliminate(space: PlanSpace, plan: list[int]) -> list[int]:
    """Action elimination: drop each step that, with the later steps it alone enabled,
    the goal does not need. Returns the shortened plan (the same list when none is)."""
    packed = space.packed
    i = 0
    state = space.start  # the state before step i
    while i < len(plan):
        kept: list[int] = []
        current = state
        for j in range(i + 1, len(plan)):
            step = plan[j]
            if space.runs(step, current):
                current = packed.apply(step, current)
                kept.append(step)
        if space.goal(current):
            plan = plan[:i] + kept  # step i and what only it enabled are gone
            continue  # the step now at i is tried from the same state
        state = packed.apply(plan[i], state)
        i += 1
    return plan


def improve(space: PlanSpace, plan: Sequence[GroundAction], limits: Limits, floor: int = 0
            ) -> Improvement | None:
    """A better plan than `plan` (valid from the start, reaching the goal), or None.

    Stops at the deadline of `limits`, or when it says to stop, with the best plan
    found by then; and once the plan has `floor` steps, a lower bound on the steps of
    any plan (bound.py) where every action costs the same.
    """
    numbers = space.encode(plan)
    if numbers is None or not space.reachable or not space.valid(numbers):
        return None
    current = eliminate(space, numbers)
    result = Improvement(list(plan), len(plan), eliminated=len(numbers) - len(current))
    if limits.max_states > 0 and len(current) > floor:
        current = _search(space, current, result, limits, floor)
    if space.measure(current) >= space.measure(numbers):
        return None
    result.steps = [space.packed.actions[i] for i in current]
    return result


def _search(space: PlanSpace, plan: list[int], result: Improvement, limits: Limits,
            floor: int = 0) -> list[int]:
    """Plan-neighbourhood search from `plan`: the best plan found within `limits`, or
    the first of `floor` steps."""

    def around(plan: list[int], previous: Neighbourhood | None = None) -> Neighbourhood:
        return Neighbourhood(space, space.trajectory(plan), limits, previous)

    area, depth = around(plan), 1
    found_at = len(area.states)  # states of the neighbourhood that last improved the plan
    try:
        while not limits.passed():
            while area.depth < depth and not area.closed and not area.full:
                area.grow()
            result.looked_at(area.depth, len(area.states), area.closed)
            better = area.cheapest(space.measure(plan))
            if better is not None and space.measure(better) < space.measure(plan):
                shorter = eliminate(space, better)
                result.shortened(len(plan) - len(better), len(better) - len(shorter))
                plan, found_at = shorter, len(area.states)
                if len(plan) <= floor:
                    return plan  # no plan has fewer steps
                area = around(plan, area)  # then as far out around the new trajectory
                continue
            if area.closed or area.full or len(area.states) >= _patience(
                    len(plan), found_at, floor):
                return plan
            depth += 1
    except OutOfTime:
        pass
    return plan


def _patience(steps: int, found_at: int, floor: int) -> int:
    """States a neighbourhood may reach without a better plan before the search stops."""
    per_step = min(PATIENCE_PER_STEP * steps, PATIENCE_PER_STEP_MAX)
    states = max(PATIENCE_STATES, per_step, PATIENCE * found_at)
    return min(states, SLACK_STATES * (steps - floor)) if floor else states
