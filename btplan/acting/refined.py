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
from collections.abc import Sequence
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
        self.trusted: set[str] = set()
        """Onward values whose measures count: an action with them failed (`failed`)."""
        self.given: dict[tuple[str, str], set[str]] = {}
        """Values given per (action, parameter)."""
        self._by_name = {a.name: a for a in task.domain.actions}
        self.unsure = {p.predicate for a in task.domain.actions for p in a.preconditions
                       if not p.positive}
        self.current: Grounding | None = None
        self._keys: list[tuple[ActionTemplate, tuple[str, ...]]] = []

    @property
    def task(self) -> Task:
        """The task with the values refined so far as objects."""
        return self.current.task if self.current is not None else self.base

    def observe(self, world: Any, steps: Sequence[GroundAction] | None = None
                ) -> frozenset[Atom]:
        """The state the baseline plans and monitors with.

        A negative precondition on a refined value (`not blocks(_, t)`) is measured
        anew first, as the tree's condition node measures it when ticked: the world
        keeps the last measure of a path planned from elsewhere, and a cube put aside
        since would still block it. Those of `steps` are measured (what the executor
        monitors), or, without steps, those of every value given (before it plans).

        Left out is such a fact about an onward value (`blocks(c, t)` for the path t to
        blue's aside spot): the world measures that path from where the robot stands
        now, but it is driven later, with blue in hand, from where blue was picked up,
        and planned again from there; measured from here it is often blocked by blue
        itself, or by a cube next to the robot now. The planner takes such a path as
        free, as a task-and-motion planner takes a motion it has not tried, until a move
        along it fails (`failed`); from then on the world's measure counts, except that
        blue never blocks the path it is carried along.
        """
        keys = self._measured() if steps is None else [
            (p.atom.predicate, p.atom.args) for a in steps for p in a.preconditions
            if not p.positive and self.values.keys() & set(p.atom.args)]
        for key in dict.fromkeys(keys):
            if not (self.onward.keys() - self.trusted) & set(key[1]):  # taken as free
                world.check(key)
        facts: frozenset[Atom] = world.facts()
        if not self.onward:
            return facts
        return frozenset(f for f in facts if not self._carried(f))

    def _carried(self, fact: Atom) -> bool:
        """Whether `fact` is left out: it names an onward value the planner takes as free
        (not yet driven in vain), or says the object a path is for stands in its way."""
        return fact.predicate in self.unsure and any(
            a in self.onward and (a not in self.trusted or self.onward[a] & set(fact.args))
            for a in fact.args)

    def failed(self, action: GroundAction) -> None:
        """An action with an onward value failed (a move to an aside spot found its way
        blocked): what the world measures about that value counts from now on."""
        self.trusted.update(a for a in action.args if a in self.onward)

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
        task, candidates = self._grown()
        if self.current is None or candidates != self._keys:
            self.current = Grounding(task, self._admitted(task, candidates, state))
            self._keys = candidates
        return self.current

    def actions(self, state: frozenset[Atom]) -> list[GroundAction]:
        """The actions `ground` plans with, as plain grounded actions (no pyperplan task):
        what the tree's last-resort search plans with (btplan.acting.departures.refined_search)."""
        task, candidates = self._grown()
        return self._admitted(task, candidates, state)

    def _grown(self) -> tuple[Task, list[tuple[ActionTemplate, tuple[str, ...]]]]:
        """The task with every value given so far, and its candidates, asked until no
        new value comes."""
        for _ in range(ROUNDS):
            task = self._with_values()
            candidates = self._candidates(task)
            if not any(v not in task.object_types for v in self.values):
                break
        return task, candidates

    def _admitted(self, task: Task, candidates: list[tuple[ActionTemplate, tuple[str, ...]]],
                  state: frozenset[Atom]) -> list[GroundAction]:
        return [a for t, args in candidates
                if (a := admit(task, t, args, self.fluent, state)) is not None]

    def _with_values(self) -> Task:
        extra = tuple(TypedName(name=v, type=t) for v, t in sorted(self.values.items())
                      if v not in self.base.object_types)
        if not extra:
            return self.base
        problem = self.base.problem.model_copy(
            update={"objects": (*self.base.problem.objects, *extra)})
        return Task(domain=self.base.domain, problem=problem)

    def _candidates(self, task: Task) -> list[tuple[ActionTemplate, tuple[str, ...]]]:
        """Every template with the arguments to ground it with: the task's objects for
        ordinary parameters, the world's values (and the goal's) for refined ones."""
        found: list[tuple[ActionTemplate, tuple[str, ...]]] = []
        for template in task.domain.actions:
            ordinary = [p for p in template.parameters if not p.refined]
            for args in itertools.product(*(task.objects_of(p.type) for p in ordinary)):
                binding = dict(zip((p.name for p in ordinary), args))
                choices = [self._choices(template, binding, p.name) for p in template.parameters]
                found.extend((template, full) for full in itertools.product(*choices))
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
        named = [o for o in self._goal_values(template, name, binding) if o not in given]
        return [*given, *named]

    def _goal_values(self, template: ActionTemplate, name: str,
                     binding: dict[str, str]) -> list[str]:
        """The objects the goal binds `name` to through an effect whose other bound
        arguments agree with it (on(c, l) with c = green, for the goal on(green, goal):
        goal), as the tree binds it when it expands that goal; sorted by name."""
        found = set()
        free = {p.name for p in template.parameters}
        for e in template.effects:
            if not e.positive or name not in e.args:
                continue
            i = e.args.index(name)
            for g in self.base.goal_literals:
                if g.positive and g.atom.predicate == e.predicate \
                        and len(g.atom.args) == len(e.args) \
                        and all(binding.get(a, a) == v or (a in free and a not in binding)
                                for j, (a, v) in enumerate(zip(e.args, g.atom.args))
                                if j != i):
                    found.add(g.atom.args[i])
        return sorted(found)
