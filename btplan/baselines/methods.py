"""Sequential-plan executors that the blended loop is measured against.

The paper's claim (Problem 1) is that a backchained BT copes with external agents more
cheaply than re-planning; that claim is only worth something against the baselines a
user would really pick. Both here plan with pyperplan's greedy best-first search and
h_FF, on the task grounded once per run (btplan.acting.strips; in a world that refines
values the task does not declare, grounded with them as they come: btplan.acting.refined),
and execute the plan one step at a time in the same
world, with the same agents, under the same tick budget as the blended loop:

- `replan` monitors the whole remaining plan every tick and replans from scratch as
  soon as it no longer reaches the goal from the observed state;
- `repair` looks at the next step only; when it cannot run (or failed) it first
  reuses the rest of its plan (an agent may have done steps for it), then plans a
  short prefix back to the rest of the plan, and replans from scratch only if that
  fails.

`replan-unlimited` is `replan` without the one-call-per-tick cap: when it too fails
within the budget, the disturbed world had no solution in time.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from typing import Any

from btplan.acting.refined import RefinedGrounding, asks_world
from btplan.acting.strips import (
    Grounding,
    check_strips,
    fact_of,
    instances,
    require_pyperplan,
)
from btplan.bt import FAILURE, RUNNING, SUCCESS
from btplan.errors import InputError
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.records import record
from btplan.worlds.agents import Agent, act_all

BASELINES = ("replan", "repair", "replan-unlimited")


@record(slots=True)
class BaselineOutcome:
    """What a baseline run did; the same measures the sweep takes from the blended loop."""

    reached: bool
    ticks: int
    actions: int
    planner_calls: int
    planning_seconds: float
    checks: int
    disturbances: int
    setup_seconds: float = 0.0
    """Grounding the task and building h_FF for its goal (once per run, before acting)."""
    reason: str = "goal reached"


class PlanExecutor:
    """A sequential plan executed one step per tick (a finished step lets the next start).

    `monitor` "plan" validates the whole rest of the plan every tick (replanning from
    scratch); "step" only the next step (plan repair). `per_tick` bounds planner calls
    per tick (None: unbounded).
    """

    def __init__(self, task: Task, world: Any, grounding: Grounding | RefinedGrounding,
                 monitor: str, per_tick: int | None = 1) -> None:
        self.task, self.world, self.grounding = task, world, grounding
        self.monitor, self.per_tick = monitor, per_tick
        self.plan: list[GroundAction] = []
        self.step = 0
        self.running: GroundAction | None = None
        self.failed = False
        self.calls, self.seconds, self.checks = 0, 0.0, 0
        self.found_none = False
        self._calls_this_tick = 0

    # --- monitoring -------------------------------------------------------------------

    def _holds(self, literals: Sequence[GroundLiteral], state: frozenset[Atom]) -> bool:
        for literal in literals:
            self.checks += 1
            if not literal.holds(state):
                return False
        return True

    def _reaches_goal(self, start: int, state: frozenset[Atom]) -> bool:
        """Does plan[start:] run from `state` and end with the goal true?"""
        for action in self.plan[start:]:
            if not self._holds(action.preconditions, state):
                return False
            state = action.apply(state)
        return self._holds(self.task.goal_literals, state)

    def done(self) -> bool:
        """Whether the goal holds in the world's facts now. Every literal read counts in
        `checks`, the cost the sweep sets against the blended loop's condition checks."""
        return self._holds(self.task.goal_literals, self.world.facts())

    # --- planning ---------------------------------------------------------------------

    def _call(self, state: frozenset[Atom], goal: frozenset[str] | None = None
              ) -> list[GroundAction] | None:
        self._calls_this_tick += 1
        self.calls += 1
        started = time.process_time()
        found = self.grounding.plan(state, goal)
        self.seconds += time.process_time() - started
        self.found_none = found is None
        return found

    def _may_call(self) -> bool:
        return self.per_tick is None or self._calls_this_tick < self.per_tick

    def _replan(self, state: frozenset[Atom]) -> bool:
        found = self._call(state)
        self.plan, self.step = found or [], 0
        return found is not None

    def _repair(self, state: frozenset[Atom]) -> bool:
        """Reuse the rest of the plan, else plan back to it, else replan from scratch."""
        for start in range(len(self.plan), self.step - 1, -1):  # the shortest rest first
            if self._reaches_goal(start, state):
                self.step = start
                return True
        need = _regress(self.plan[self.step:], self.grounding.task)
        if need is not None and self.step < len(self.plan):
            prefix = self._call(state, frozenset(str(a) for a in need))
            if prefix is not None:
                self.plan, self.step = prefix + self.plan[self.step:], 0
                return True
            if not self._may_call():
                # No way back: the next tick replans from scratch instead of searching
                # for it again (the tick's one call is used up).
                self.plan, self.step = [], 0
                return False
        return self._replan(state)

    def _ensure_plan(self) -> bool:
        """Make sure the next step is worth starting; False when no plan is at hand."""
        if self.monitor == "plan":
            state = self.grounding.observe(self.world, self.plan[self.step:])
            if self._reaches_goal(self.step, state):
                return True
            return self._may_call() and self._replan(self.grounding.observe(self.world))
        nxt = self.plan[self.step] if self.step < len(self.plan) else None
        state = self.grounding.observe(self.world, [nxt] if nxt is not None else [])
        if not self.failed and nxt is not None and self._holds(nxt.preconditions, state):
            return True
        self.failed = False
        return self._may_call() and self._repair(self.grounding.observe(self.world))

    # --- one tick ---------------------------------------------------------------------

    def tick(self) -> bool:
        """One tick; True when the goal holds."""
        self._calls_this_tick = 0
        if self.running is not None and self.monitor == "plan" and not self.done():
            if not self._ensure_plan():
                return False
            if self.plan[self.step].key != self.running.key:
                self.world.halt(self.running.key)
                self.running = None
        while True:
            if self.done():
                return True
            if self.running is None:
                if not self._ensure_plan():
                    return False
                action = self.plan[self.step]
                status = self.world.start(action.key)
            else:
                action = self.running
                status = self.world.step(action.key)
            self.running = action if status is RUNNING else None
            if status is SUCCESS:
                self.step += 1
                continue
            if status is FAILURE:
                self.failed = True
                self.grounding.failed(action)
            return self.done()


def _regress(rest: Sequence[GroundAction], task: Task) -> frozenset[Atom] | None:
    """The atoms that must hold for `rest` to run and reach the goal (None: it never can)."""
    need = {g.atom for g in task.goal_literals}
    for action in reversed(rest):
        if any(action.deletes(a) for a in need):
            return None
        need = (need - set(action.add)) | {fact_of(n) for p in action.preconditions
                                            for n in instances(p, task)}
    return frozenset(need)


def run_baseline(task: Task, world: Any, agents: Sequence[Agent], method: str,
                 max_ticks: int, grounding: Grounding | RefinedGrounding | None = None
                 ) -> BaselineOutcome:
    """Execute `method` (one of BASELINES) in `world` with `agents` acting before each tick.

    Grounding the task (and h_FF for its goal) is timed apart, as `setup_seconds`:
    it depends on the task only, as the blended loop's relaxed model does; the
    searches are `planning_seconds`. When the world supplies values the task does not
    declare (trajectories in the simulator), grounding asks it for them inside each
    planner call (btplan.acting.refined), and that time is planning time.
    """
    if method not in BASELINES:
        raise InputError(f"unknown baseline '{method}'", None, "one of " + ", ".join(BASELINES))
    require_pyperplan()
    check_strips(task)
    started = time.process_time()
    if grounding is None:
        grounding = RefinedGrounding(task, world) if asks_world(task) else Grounding(task)
    grounding.prepare()
    setup = time.process_time() - started
    executor = PlanExecutor(task, world, grounding, "step" if method == "repair" else "plan",
                            None if method == "replan-unlimited" else 1)
    reached, ticks, seen = False, max_ticks, 0
    for tick in range(1, max_ticks + 1):
        seen += len(act_all(agents, world, tick))
        if executor.tick():
            reached, ticks = True, tick
            break
    reason = "goal reached" if reached else (
        f"the goal was not reached within {max_ticks} ticks"
        + (" (the last search found no plan)" if executor.found_none else ""))
    return BaselineOutcome(reached, ticks, len(world.executed), executor.calls,
                           executor.seconds, executor.checks, seen, setup, reason)
