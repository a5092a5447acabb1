"""Refinement by constraints: the values of a `refined` parameter that its `where` holds for.

A world that has nothing continuous to sample (a symbolic world, a robot whose places
are named in its facts) refines a parameter by the objects of its type that satisfy the
template's `where` constraints in the current facts. The symbolic world refines this
way, and so does the acting loop for a robot that declares no `refine` of its own.
"""

from __future__ import annotations

from collections.abc import Callable, Container, Mapping

from btplan.model import EQUALITY, ActionTemplate, Atom, Literal, Parameter, Task

__all__ = ["ConstraintRefiner", "decided"]


class ConstraintRefiner:
    """`refine(template, binding, parameter)` over the facts `facts()` gives now."""

    def __init__(self, task: Task, facts: Callable[[], Container[Atom]]) -> None:
        self.task = task
        self.facts = facts
        self._objects: dict[str, tuple[str, ...]] = {}
        self._goal_names: frozenset[str] | None = None

    def __call__(self, template: ActionTemplate, binding: Mapping[str, str],
                 parameter: Parameter) -> list[str]:
        """Objects of the parameter's type that satisfy the template's `where` constraints.

        Constraints that mention other, still unbound parameters do not filter here;
        the planner checks them once those are bound. A value the goal names (the goal
        region) is where the goal wants its own objects: it is offered only when nothing
        else fits, so an obstacle is put aside, not on the goal. Sorted by name, so the
        answer is the same on every run.
        """
        # Which constraints are decided depends on the names bound, not on the values:
        # the same for every candidate. The objects of a type and the goal's names depend
        # on the task only; only the constraints are read from the state, on every call.
        checks = decided(template, {**binding, parameter.name: ""})
        state = self.facts()
        out: list[str] = []
        for candidate in self._objects_of(parameter.type):
            trial = dict(binding)
            trial[parameter.name] = candidate
            if all(holds(c, trial, state) for c in checks):
                out.append(candidate)
        named = self._goal_names
        if named is None:
            named = self._goal_names = frozenset(
                a for g in self.task.goal_literals for a in g.atom.args)
        return [c for c in out if c not in named] or out

    def _objects_of(self, type_name: str) -> tuple[str, ...]:
        """`Task.objects_of`, remembered per type: the task's objects do not change."""
        found = self._objects.get(type_name)
        if found is None:
            found = self._objects[type_name] = self.task.objects_of(type_name)
        return found


def holds(literal: Literal, binding: Mapping[str, str], state: Container[Atom]) -> bool:
    """Whether a template literal, its parameters bound by `binding`, holds in `state`."""
    args = tuple(binding.get(a, a) for a in literal.args)
    if literal.predicate == EQUALITY:
        value = args[0] == args[1]
    else:
        value = Atom(literal.predicate, args) in state
    return value is literal.positive


def decided(template: ActionTemplate, binding: Mapping[str, str]) -> list[Literal]:
    """The constraints whose parameters are all bound; constants count as bound."""
    names = {p.name for p in template.parameters}
    return [
        c for c in template.constraints if all(a in binding or a not in names for a in c.args)
    ]
