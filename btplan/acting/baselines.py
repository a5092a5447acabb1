"""Sequential-plan executors that the blended loop is measured against.

The paper's claim (Problem 1) is that a backchained BT copes with external agents more
cheaply than re-planning; that claim is only worth something against the baselines a
user would really pick. Both here plan with pyperplan's greedy best-first search and
h_FF, grounded once per run, and execute the plan one step at a time in the same
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

import itertools
import time
from collections.abc import Sequence
from typing import Any

from btplan.bt import FAILURE, RUNNING, SUCCESS
from btplan.errors import InputError, MissingExtraError
from btplan.model import (
    EQUALITY,
    WILDCARD,
    Atom,
    GroundAction,
    GroundLiteral,
    Task,
    instantiate,
)
from btplan.records import record
from btplan.worlds.agents import Agent, act_all

BASELINES = ("replan", "repair", "replan-unlimited")


def require_pyperplan() -> None:
    """Refuse the baselines up front when pyperplan is missing, with the extra to install."""
    try:
        import pyperplan  # type: ignore[import-untyped]  # noqa: F401
    except ImportError:
        raise MissingExtraError(
            "the replan and repair baselines need pyperplan: pip install 'btplan[replan]'"
        ) from None


def check_strips(task: Task) -> None:
    """pyperplan states STRIPS only: positive goals (negative preconditions are compiled)."""
    negative = [str(g) for g in task.goal_literals if not g.positive]
    if negative:
        raise InputError(f"the baselines plan STRIPS tasks only; this one has negative "
                         f"goals ({', '.join(negative[:3])})", None,
                         "compare with --method btplan only")


def fact_of(literal: GroundLiteral) -> Atom:
    """The STRIPS fact for a precondition: a negative one (`not blocks(_, t)`) is a fact
    of its own, true in a state where the literal holds."""
    return literal.atom if literal.positive else Atom(f"not {literal.atom.predicate}",
                                                      literal.atom.args)


class Grounding:
    """Every grounded action of a task as pyperplan operators, built once per run.

    `where` constraints on predicates that actions or agents may change become
    preconditions; the others filter the groundings. A negative precondition becomes a
    fact of its own (fact_of), made true by actions that delete its atom and false by
    actions that add it; a wildcard one (`not blocks(_, t)`) becomes one such fact per
    object the wildcard can stand for, all needed: exact STRIPS.
    """

    def __init__(self, task: Task) -> None:
        from pyperplan.task import Operator  # type: ignore[import-untyped]

        fluent = {e.predicate for a in task.domain.actions for e in a.effects}
        state = task.initial_state
        self.actions: list[GroundAction] = []
        for template in task.domain.actions:
            names = [p.name for p in template.parameters]
            domains = [task.objects_of(p.type) for p in template.parameters]
            for args in itertools.product(*domains):
                binding = dict(zip(names, args))
                extra: list[GroundLiteral] = []
                ok = True
                checks = [*template.constraints,
                          *(c for c in template.preconditions if c.predicate == EQUALITY)]
                for c in checks:
                    ground = tuple(binding.get(a, a) for a in c.args)
                    if c.predicate == EQUALITY:
                        ok = (ground[0] == ground[1]) is c.positive
                    elif c.predicate in fluent or not c.positive:
                        extra.append(GroundLiteral(Atom(c.predicate, ground), c.positive))
                        continue
                    else:
                        ok = (Atom(c.predicate, ground) in state) is c.positive
                    if not ok:
                        break
                if ok:
                    action = instantiate(template, tuple(args))
                    pre = (*action.preconditions, *(e for e in extra if e.positive))
                    self.actions.append(action.model_copy(update={"preconditions": pre}))
        universe = set(state).union(*(a.add for a in self.actions))
        universe.update(p.atom for a in self.actions for p in a.preconditions if p.positive)
        universe.update(g.atom for g in task.goal_literals)
        self.negatives = sorted({n for a in self.actions for p in a.preconditions
                                 if not p.positive for n in instances(p, task)})
        plain = frozenset(universe)
        universe.update(fact_of(n) for n in self.negatives)
        self.universe = frozenset(universe)
        self.by_name = {str(a): a for a in self.actions}
        self.operators = [
            Operator(str(a), frozenset(str(fact_of(n)) for p in a.preconditions
                                       for n in instances(p, task)),
                     frozenset(str(x) for x in a.add)
                     | {str(fact_of(n)) for n in self.negatives if _undoes(a, n)},
                     frozenset(str(x) for x in plain if a.deletes(x))
                     | {str(fact_of(n)) for n in self.negatives if _breaks(a, n)})
            for a in self.actions
        ]
        self.facts = {str(x) for x in self.universe}
        self.goal = frozenset(str(g.atom) for g in task.goal_literals)
        self._heuristics: dict[frozenset[str], Any] = {}

    def _strips(self, state: frozenset[Atom], target: frozenset[str]) -> Any:
        from pyperplan.task import Task as StripsTask

        init = frozenset(str(x) for x in state if x in self.universe) | {
            str(fact_of(n)) for n in self.negatives if n.holds(state)}
        return StripsTask("replan", self.facts, init, target, self.operators)

    def _heuristic(self, strips: Any, target: frozenset[str]) -> Any:
        """h_FF for `target`: it depends on the goal only, not on the initial state."""
        from pyperplan.heuristics.relaxation import hFFHeuristic  # type: ignore[import-untyped]

        heuristic = self._heuristics.get(target)
        if heuristic is None:
            heuristic = self._heuristics[target] = hFFHeuristic(strips)
        return heuristic

    def prepare(self) -> None:
        """Build h_FF for the task's goal now, as part of the task's set-up."""
        self._heuristic(self._strips(frozenset(), self.goal), self.goal)

    def plan(self, state: frozenset[Atom], goal: frozenset[str] | None = None
             ) -> list[GroundAction] | None:
        """A plan from `state` to `goal` (the task's by default) by GBFS with h_FF, or None."""
        from pyperplan.search import greedy_best_first_search  # type: ignore[import-untyped]

        target = self.goal if goal is None else goal
        strips = self._strips(state, target)
        heuristic = self._heuristic(strips, target)
        found = greedy_best_first_search(strips, heuristic)
        return None if found is None else [self.by_name[op.name] for op in found]


def instances(literal: GroundLiteral, task: Task) -> list[GroundLiteral]:
    """A precondition as plain literals: `not blocks(_, t)` is `not blocks(o, t)` for
    every object o the wildcard can stand for (the predicate's parameter type)."""
    if literal.positive or WILDCARD not in literal.atom.args:
        return [literal]
    declared = task.domain.predicate_map[literal.atom.predicate].parameters
    choices = [task.objects_of(p.type) if a == WILDCARD else (a,)
               for a, p in zip(literal.atom.args, declared)]
    return [GroundLiteral(Atom(literal.atom.predicate, args), False)
            for args in itertools.product(*choices)]


def _undoes(action: GroundAction, negative: GroundLiteral) -> bool:
    """Whether `action` makes the negated atom false."""
    return action.deletes(negative.atom)


def _breaks(action: GroundAction, negative: GroundLiteral) -> bool:
    """Whether `action` makes the negated atom true."""
    return negative.atom in action.add


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

    def __init__(self, task: Task, world: Any, grounding: Grounding, monitor: str,
                 per_tick: int | None = 1) -> None:
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
        need = _regress(self.plan[self.step:], self.task)
        if need is not None and self.step < len(self.plan):
            prefix = self._call(state, frozenset(str(a) for a in need))
            if prefix is not None:
                self.plan, self.step = prefix + self.plan[self.step:], 0
                return True
            if not self._may_call():
                return False
        return self._replan(state)

    def _ensure_plan(self) -> bool:
        """Make sure the next step is worth starting; False when no plan is at hand."""
        state = self.world.facts()
        if self.monitor == "plan":
            if self._reaches_goal(self.step, state):
                return True
            return self._may_call() and self._replan(state)
        nxt = self.plan[self.step] if self.step < len(self.plan) else None
        if not self.failed and nxt is not None and self._holds(nxt.preconditions, state):
            return True
        self.failed = False
        return self._may_call() and self._repair(state)

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
                 max_ticks: int, grounding: Grounding | None = None) -> BaselineOutcome:
    """Execute `method` (one of BASELINES) in `world` with `agents` acting before each tick.

    Grounding the task (and h_FF for its goal) is timed apart, as `setup_seconds`:
    it depends on the task only, as the blended loop's relaxed model does; the
    searches are `planning_seconds`.
    """
    if method not in BASELINES:
        raise InputError(f"unknown baseline '{method}'", None, "one of " + ", ".join(BASELINES))
    require_pyperplan()
    check_strips(task)
    started = time.process_time()
    grounding = grounding or Grounding(task)
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
