"""Finding the grounded actions that make a condition true: GetAllActTemplatesFor.

The domain is indexed by the predicate and sign of each effect, so the achievers of
a condition are found without scanning every action (Algorithm 2, line 2). Each
matching effect is unified with the condition, the remaining parameters are bound
(`grounding.bindings`), and the groundings are ranked best first.
"""

from __future__ import annotations

import math

from btplan.model import (
    WILDCARD,
    ActionTemplate,
    Atom,
    GroundAction,
    GroundLiteral,
    Literal,
    Task,
    instantiate,
    matches,
)
from btplan.planner.grounding import Objects, bindings, unify
from btplan.planner.reach import building
from btplan.planner.heuristic import RelaxedModel
from btplan.planner.mutex import Mutexes
from btplan.planner.options import PlannerOptions
from btplan.planner.protocol import Refiner
from btplan.planner.search import SubgoalSearch

ALL = 1 << 30
"""A limit on achievers that keeps them all."""


class _Shared:
    """What does not depend on the options: built once per task and shared."""

    def __init__(self) -> None:
        self.objects: Objects | None = None
        self.made: dict[tuple[str, tuple[str, ...]], GroundAction] = {}
        self.relaxed: RelaxedModel | None = None
        self.mutexes: Mutexes | None = None
        self.search: SubgoalSearch | None = None


class AchieverIndex:
    """Effects of the domain indexed by (predicate, sign), with a lazily built h_add model."""

    def __init__(
        self, task: Task, options: PlannerOptions | None = None, like: AchieverIndex | None = None
    ) -> None:
        """`like`: an index of the same task whose groundings, relaxed model and mutexes
        are shared (built once, however many planning attempts use them)."""
        self.task = task
        self.options = options or PlannerOptions()
        self._shared: _Shared = like._shared if like is not None else _Shared()
        self._by_effect: dict[tuple[str, bool], list[tuple[ActionTemplate, Literal]]] = {}
        for template in task.domain.actions:
            for effect in template.effects:
                key = (effect.predicate, effect.positive)
                self._by_effect.setdefault(key, []).append((template, effect))
        self.objects = self._shared.objects or Objects(task)
        self._shared.objects = self.objects

    @property
    def relaxed(self) -> RelaxedModel:
        shared = self._shared
        if shared.relaxed is None:
            shared.relaxed = RelaxedModel(self.task, objects=self.objects, ground=self.ground)
        return shared.relaxed

    def ground(self, template: ActionTemplate, args: tuple[str, ...]) -> GroundAction:
        """`instantiate`, remembered: the same groundings come up on every expansion."""
        made = self._shared.made
        action = made.get((template.name, args))
        if action is None:
            action = made[(template.name, args)] = self.task.instantiate(template, args)
        return action

    def has_effect(self, condition: GroundLiteral) -> bool:
        """Whether any action template has an effect of this predicate and sign."""
        return bool(self._by_effect.get((condition.atom.predicate, condition.positive)))

    @property
    def mutexes(self) -> Mutexes:
        """h^2 mutexes from the initial state, built on first use."""
        shared = self._shared
        if shared.mutexes is None:
            relaxed = self.relaxed
            with building():
                shared.mutexes = Mutexes(relaxed.actions, self.task.initial_state,
                                         self.task.domain)
        return shared.mutexes

    @property
    def subgoal_search(self) -> SubgoalSearch:
        """The last-resort search over the relaxed model's groundings, built on first use."""
        shared = self._shared
        if shared.search is None:
            relaxed = self.relaxed
            with building():
                shared.search = SubgoalSearch(relaxed.actions)
        return shared.search

    def achievers(
        self,
        condition: GroundLiteral,
        state: frozenset[Atom],
        refine: Refiner | None,
        limit: int | None = None,
    ) -> list[GroundAction]:
        """Grounded actions whose effects make `condition` hold, best first, bounded.

        Ranking (the paper leaves the order open; its Remark suggests cheap first):
        cost plus, with the heuristic on, the h_add estimate of the preconditions;
        then the number of preconditions that fail now; then the name, for ties.
        """
        found: dict[tuple[str, tuple[str, ...]], GroundAction] = {}
        if not condition.positive and WILDCARD in condition.atom.args:
            # `not blocks(_, t)`: undo each instance that holds now; guards() says which.
            for atom in instances(condition, state):
                for action in self.achievers(GroundLiteral(atom, False), state, refine, ALL):
                    found.setdefault(action.key, action)
            scored = sorted((self._rank(a, state), a) for a in found.values())
            return [a for score, a in scored if score[0] < math.inf][: limit or self.options.max_alternatives]
        reachable = self.relaxed.costs(state) if self.options.prune_bindings else None
        for template, effect in self._by_effect.get((condition.atom.predicate, condition.positive), []):
            partial = unify(self.task, template, effect, condition.atom, self.objects)
            if partial is None:
                continue
            for binding in bindings(
                self.task, template, partial, state, refine, self.options.max_bindings,
                self.objects, reachable=reachable,
            ):
                args = tuple(binding[p.name] for p in template.parameters)
                action = self.ground(template, args)
                if _makes_true(action, condition) and action.key not in found:
                    found[action.key] = action
        candidates = list(found.values())
        if self.options.mutexes:
            candidates = [a for a in candidates if not self._impossible(a)]
        scored = sorted((self._rank(a, state), a) for a in candidates)
        ranked = [a for score, a in scored if score[0] < math.inf]
        return ranked[: limit or self.options.max_alternatives]

    def _impossible(self, action: GroundAction) -> bool:
        """Whether two preconditions of `action` exclude each other (h^2): it never runs.

        Barman's fill-shot(shot1, i, left, left, d) needs holding(left, shot1) and
        handempty(left); h_add ranks it like any other grounding.
        """
        mutexes = self.mutexes
        pre = [p for p in action.preconditions if p.positive and mutexes.knows(p.atom)]
        return any(mutexes.exclusive(a, b) for i, a in enumerate(pre) for b in pre[i + 1:])

    def _rank(self, action: GroundAction, state: frozenset[Atom]) -> tuple[float, int, str]:
        failing = sum(1 for p in action.preconditions if not p.holds(state))
        estimate = 0.0
        if self.options.heuristic:
            estimate = self._estimate(action, state)
        return (action.cost + estimate, failing, str(action))

    def _estimate(self, action: GroundAction, state: frozenset[Atom]) -> float:
        atoms = [p.atom for p in action.preconditions if p.positive and p.atom not in state]
        if not atoms:
            return 0.0
        known = self.task.object_types
        if all(a in known for atom in atoms for a in atom.args):
            return self.relaxed.estimate(state, atoms)
        # Values a backend refined (poses, trajectories) are unknown to the relaxed
        # model; count such preconditions instead of calling them unreachable.
        return float(len(atoms))


def instances(condition: GroundLiteral, state: frozenset[Atom]) -> list[Atom]:
    """The atoms of `state` that a wildcard condition's pattern matches, sorted."""
    return sorted(a for a in state if matches(condition.atom, a))


def guards(action: GroundAction, condition: GroundLiteral, state: frozenset[Atom]
           ) -> tuple[GroundLiteral, ...]:
    """What an achiever of a wildcard condition is for: the instances it undoes.

    `not blocks(_, t)` is achieved by undoing each `blocks(c, t)` that holds; the
    alternative for c is guarded by `blocks(c, t)`, so that once c is out of the way it
    is not run again (picking c back up) when another object blocks t later.
    """
    if condition.positive or WILDCARD not in condition.atom.args:
        return ()
    return tuple(GroundLiteral(a, True) for a in instances(condition, state)
                 if action.deletes(a))


def _makes_true(action: GroundAction, condition: GroundLiteral) -> bool:
    if condition in action.preconditions:
        return False  # needs what it would achieve: never useful in a fallback
    if condition.positive:
        return condition.atom in action.add
    return action.deletes(condition.atom)
