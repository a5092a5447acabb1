"""Every grounded action of a STRIPS task as pyperplan operators: what the baselines plan on.

Negative preconditions are compiled to facts of their own and a wildcard one to one fact
per object it may stand for, so that pyperplan's STRIPS search is exact on these tasks.
The task's objects give the groundings here; btplan.acting.refined adds the values a
world refines (trajectories, poses in the simulator).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

from btplan.errors import InputError, MissingExtraError
from btplan.model import (
    EQUALITY,
    ActionTemplate,
    Atom,
    GroundAction,
    GroundLiteral,
    Task,
    instantiate,
)
from btplan.grounding import wildcard_instances


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

    def __init__(self, task: Task, actions: Sequence[GroundAction] | None = None) -> None:
        from pyperplan.task import Operator  # type: ignore[import-untyped]

        self.task = task
        """The task grounded: its objects are what `not blocks(_, t)` may stand for."""
        state = task.initial_state
        self.actions = list(actions) if actions is not None else ground_all(task)
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

    def observe(self, world: Any, steps: Sequence[GroundAction] | None = None
                ) -> frozenset[Atom]:
        """The state to plan and monitor with: the world's facts as they are."""
        return world.facts()  # type: ignore[no-any-return]

    def failed(self, action: GroundAction) -> None:
        """An action failed in the world: nothing to learn, the facts say why."""

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


def ground_all(task: Task) -> list[GroundAction]:
    """Every action of `task` with its parameters bound to the task's objects."""
    fluent = {e.predicate for a in task.domain.actions for e in a.effects}
    found: list[GroundAction] = []
    for template in task.domain.actions:
        domains = [task.objects_of(p.type) for p in template.parameters]
        for args in itertools.product(*domains):
            action = admit(task, template, tuple(args), fluent, task.initial_state)
            if action is not None:
                found.append(action)
    return found


def admit(task: Task, template: ActionTemplate, args: tuple[str, ...], fluent: set[str],
          state: frozenset[Atom]) -> GroundAction | None:
    """`template` bound to `args`, or None when a static `where` rules it out.

    A `where` on a predicate that actions or agents may change becomes a precondition;
    the others are decided in `state` now.
    """
    binding = dict(zip((p.name for p in template.parameters), args))
    extra: list[GroundLiteral] = []
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
            return None
    action = instantiate(template, args)
    pre = (*action.preconditions, *(e for e in extra if e.positive))
    return action.model_copy(update={"preconditions": pre})


def instances(literal: GroundLiteral, task: Task) -> list[GroundLiteral]:
    """A precondition as plain literals: `not blocks(_, t)` is `not blocks(o, t)` for
    every object o the wildcard can stand for (the predicate's parameter type)."""
    return [literal] if literal.positive else wildcard_instances(literal, task)


def _undoes(action: GroundAction, negative: GroundLiteral) -> bool:
    """Whether `action` makes the negated atom false."""
    return action.deletes(negative.atom)


def _breaks(action: GroundAction, negative: GroundLiteral) -> bool:
    """Whether `action` makes the negated atom true."""
    return negative.atom in action.add
