"""The baselines' grounding when the world supplies values the task does not declare.

In the simulator a trajectory or a pose to put an obstacle aside is no object of the
problem: it exists once the world refines it (RefineActions: a path planned with OMPL,
a spot sampled off every known path). A task-and-motion replanner grounds such
parameters by asking the world at planning time, as the tree does when it expands an
action: one trajectory per location to drive to, one pose per object to put aside.
A value the world names (pose2) is a location in its turn, so grounding goes round
until no new value appears; the world answers the same question with the same name,
so later planner calls ask again cheaply and ground anew only when a new value came.
The time the world takes to answer is part of the planner call that asked.
"""

from __future__ import annotations

import itertools
from typing import Any

from btplan.acting.strips import Grounding, admit
from btplan.errors import InputError
from btplan.model import ActionTemplate, Atom, GroundAction, Task, TypedName

ROUNDS = 4
"""Grounding passes per planner call at most: the second grounds the values the first
was given (a trajectory to a pose sampled in the first), and the world repeats its
answers, so a third finds nothing new."""


def asks_world(task: Task) -> bool:
    """Whether a refined parameter has a type the task declares no object of: grounding
    the task alone would leave out every action that has it (MoveTo without trajectories)."""
    return any(p.refined and not task.objects_of(p.type)
               for a in task.domain.actions for p in a.parameters)


class RefinedGrounding:
    """`Grounding` over the task's objects and the values `world.refine` gives for them.

    It has Grounding's `task`, `prepare` and `plan`, so the plan executor uses either.
    A refined parameter takes the values the world gives for the action's ordinary
    parameters, and the objects the goal binds it to (the goal region a cube is placed
    on), as the tree binds it from the condition it expands.
    """

    def __init__(self, task: Task, world: Any) -> None:
        if not callable(getattr(world, "refine", None)):
            raise InputError("the baselines need the world to refine the values the task "
                             "does not declare (trajectories, poses)", None,
                             "compare with --method btplan only")
        self.base, self.world = task, world
        self.values: dict[str, str] = {}
        """Every value the world gave so far, with the type of the parameter it came for."""
        self.fluent = {e.predicate for a in task.domain.actions for e in a.effects}
        self.origin: dict[str, frozenset[str]] = {}
        """The task objects each value was given for (pose1: blue; the path to pose1: blue)."""
        self.onward: dict[str, frozenset[str]] = {}
        """Values given for a binding that names another given value (a trajectory refined
        for MoveTo(pose1, t): the path to a spot chosen to put blue aside), with the
        objects that value was given for, through the chain (blue)."""
        self.given: dict[tuple[str, str], set[str]] = {}
        """Values given per (action, parameter)."""
        self._by_name = {a.name: a for a in task.domain.actions}
        self.unsure = {p.predicate for a in task.domain.actions for p in a.preconditions
                       if not p.positive}
        self.current: Grounding | None = None
        self._keys: tuple[tuple[str, tuple[str, ...]], ...] = ()

    @property
    def task(self) -> Task:
        """The task with the values refined so far as objects."""
        return self.current.task if self.current is not None else self.base

    def observe(self, world: Any) -> frozenset[Atom]:
        """The state the baseline plans and monitors with.

        A negative precondition on a refined value (`not blocks(_, t)`) is measured
        anew first, as the tree's condition node measures it when ticked: the world
        keeps the last measure of a path planned from elsewhere, and a cube put aside
        since would still block it. Left out is such a fact that names an onward value
        with the object it was given for (`blocks(blue, t)` for the path t to blue's aside
        spot): the world measures that path from where the robot stands now, but it is
        driven later, with blue in hand, from where blue was picked up, and planned again
        from there; measured from here it is often blocked by the very obstacle it is for,
        and nothing could ever put that obstacle aside. Another cube on that path blocks it.
        """
        for predicate, args in self._measured():
            world.check((predicate, args))
        facts: frozenset[Atom] = world.facts()
        if not self.onward:
            return facts
        return frozenset(f for f in facts if not self._carried(f))

    def _carried(self, fact: Atom) -> bool:
        """Whether `fact` says the object a path is for stands in that path's way."""
        return fact.predicate in self.unsure and any(
            a in self.onward and self.onward[a].intersection(fact.args) for a in fact.args)

    def _measured(self) -> list[tuple[str, tuple[str, ...]]]:
        """The negative preconditions on refined values, bound to each value given."""
        found: list[tuple[str, tuple[str, ...]]] = []
        for (template, name), values in sorted(self.given.items()):
            for p in self._by_name[template].preconditions:
                if not p.positive and name in p.args:
                    found.extend((p.predicate, tuple(v if a == name else a for a in p.args))
                                 for v in sorted(values))
        return found

    def prepare(self) -> None:
        """Nothing to build before acting: the values come from the world when planning."""

    def plan(self, state: frozenset[Atom], goal: frozenset[str] | None = None
             ) -> list[GroundAction] | None:
        """Ground against the world as it answers now, then plan as `Grounding.plan`."""
        return self.ground(state).plan(state, goal)

    def ground(self, state: frozenset[Atom]) -> Grounding:
        """The grounding with every value the world gives now (rebuilt only when it grew)."""
        for _ in range(ROUNDS):
            task = self._with_values()
            actions = self._actions(task, state)
            if not any(v not in task.object_types for v in self.values):
                break
        if self.current is None or tuple(a.key for a in actions) != self._keys:
            self.current = Grounding(task, actions)
            self._keys = tuple(a.key for a in actions)
        return self.current

    def _with_values(self) -> Task:
        extra = tuple(TypedName(name=v, type=t) for v, t in sorted(self.values.items())
                      if v not in self.base.object_types)
        if not extra:
            return self.base
        problem = self.base.problem.model_copy(
            update={"objects": (*self.base.problem.objects, *extra)})
        return Task(domain=self.base.domain, problem=problem)

    def _actions(self, task: Task, state: frozenset[Atom]) -> list[GroundAction]:
        found: list[GroundAction] = []
        for template in task.domain.actions:
            ordinary = [p for p in template.parameters if not p.refined]
            for args in itertools.product(*(task.objects_of(p.type) for p in ordinary)):
                binding = dict(zip((p.name for p in ordinary), args))
                choices = [self._choices(template, binding, p.name) for p in template.parameters]
                for full in itertools.product(*choices):
                    action = admit(task, template, full, self.fluent, state)
                    if action is not None:
                        found.append(action)
        return found

    def _choices(self, template: ActionTemplate, binding: dict[str, str],
                 name: str) -> list[str]:
        if name in binding:
            return [binding[name]]
        parameter = next(p for p in template.parameters if p.name == name)
        given = list(self.world.refine(template, binding, parameter))
        self.given.setdefault((template.name, name), set()).update(given)
        origin = frozenset().union(*(self.origin.get(v, ()) if v in self.values else (v,)
                                     for v in binding.values()))
        for value in given:
            self.values.setdefault(value, parameter.type)
            self.origin.setdefault(value, origin)
            if any(v in self.values for v in binding.values()):
                self.onward.setdefault(value, origin)
        named = [o for o in self._goal_values(template, name) if o not in given]
        return [*given, *named]

    def _goal_values(self, template: ActionTemplate, name: str) -> list[str]:
        """The objects the goal binds `name` to through an effect (on(c, l) for on(green,
        goal): goal), as the tree binds it when it expands the goal; sorted by name."""
        found = {g.atom.args[i] for e in template.effects if e.positive
                 for i, a in enumerate(e.args) if a == name
                 for g in self.base.goal_literals
                 if g.positive and g.atom.predicate == e.predicate and len(g.atom.args) > i}
        return sorted(found)
