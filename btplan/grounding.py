"""Binding template parameters to objects: the refinement step of the paper.

Beneath both rooms of planning: the PA-BT steps (btplan.planner) bind the achievers of
a condition, and the classical planner (btplan.classical) grounds the relaxed model.

Parameters are bound one at a time; after each, every `where` constraint and every
static precondition whose parameters are all bound is checked, so a wrong choice is
cut as early as possible instead of after the full cross product. Static predicates
(no action changes them) are read from the given state; `where` constraints are too,
as the language defines them as binding constraints evaluated now. A `refined`
parameter is asked of the refiner (the world backend) instead of enumerated.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Container, Iterator, Mapping

from btplan.model import (
    EQUALITY,
    WILDCARD,
    ActionTemplate,
    Atom,
    GroundLiteral,
    Literal,
    Parameter,
    Task,
)

Refiner = Callable[[ActionTemplate, Mapping[str, str], Parameter], list[str]]
"""Supplies values for a `refined` parameter, best first (the paper's RefineActions): a
world's `refine`, which grounding asks instead of enumerating the parameter's type."""

_NONE: frozenset[str] = frozenset()

PLACEHOLDER = "?"
"""Stands for a refined value when no world is asked (grounding the whole domain) and
the task declares no object of its type. Checks that mention it are satisfiable."""


class Objects:
    """The objects of every type, computed once: grounding asks for them constantly."""

    def __init__(self, task: Task) -> None:
        self._task = task
        self._of: dict[str, tuple[str, ...]] = {}
        self._sets: dict[str, frozenset[str]] = {}
        self._state: frozenset[Atom] | None = None
        self._atoms: dict[str, list[Atom]] = {}
        self._values: dict[tuple[str, int, tuple[int, ...], tuple[int, ...]],
                           dict[tuple[str | None, ...], set[str]]] = {}

    def atoms(self, state: frozenset[Atom], predicate: str) -> list[Atom]:
        """The atoms of `predicate` in `state`, indexed once per state."""
        if state is not self._state:
            self._state, self._atoms, self._values = state, {}, {}
            for atom in state:
                self._atoms.setdefault(atom.predicate, []).append(atom)
        return self._atoms.get(predicate, [])

    def values(self, state: frozenset[Atom], predicate: str, args: list[str | None],
               at: tuple[int, ...]) -> Container[str]:
        """The values v such that `state` holds `predicate(args)` with v at the places
        `at` (all the same value) and any value where `args` has None.

        Indexed once per state and pattern (the places known and `at`): grounding asks
        the same pattern for every value of the parameters bound before, and reading
        every atom of the predicate each time was most of the grounding of small
        problems' relaxed models."""
        facts = self.atoms(state, predicate)
        known = tuple(i for i, a in enumerate(args) if a is not None)
        key = (predicate, len(args), known, at)
        index = self._values.get(key)
        if index is None:
            index = self._values[key] = {}
            for atom in facts:
                if len(atom.args) != len(args):
                    continue
                seen = {atom.args[i] for i in at}
                if len(seen) == 1:
                    index.setdefault(tuple([atom.args[i] for i in known]), set()).update(seen)
        return index.get(tuple([args[i] for i in known]), _NONE)

    def of(self, type_name: str) -> tuple[str, ...]:
        """The objects of `type_name` or a subtype, sorted by name; asked once per type,
        since grounding asks again for every parameter of every binding."""
        found = self._of.get(type_name)
        if found is None:
            found = self._of[type_name] = self._task.objects_of(type_name)
            self._sets[type_name] = frozenset(found)
        return found

    def has_type(self, value: str, type_name: str) -> bool:
        """Whether `value` is an object of `type_name` or a subtype: a set lookup after the first
        question about that type."""
        if type_name not in self._sets:
            self.of(type_name)
        return value in self._sets[type_name]


def static_checks(task: Task, template: ActionTemplate) -> tuple[Literal, ...]:
    """The literals that filter bindings: `where` constraints and static preconditions."""
    static = task.domain.changed_predicates
    pre = tuple(
        p for p in template.preconditions if p.predicate == EQUALITY or p.predicate not in static
    )
    return template.constraints + pre


def bindings(
    task: Task,
    template: ActionTemplate,
    partial: Mapping[str, str],
    state: frozenset[Atom],
    refine: Refiner | None,
    limit: int,
    objects: Objects | None = None,
    optimistic: bool = False,
    reachable: Container[Atom] | None = None,
) -> Iterator[dict[str, str]]:
    """Complete bindings of `template` extending `partial`, depth first, at most `limit`.

    Objects come sorted by name and refined values in the refiner's order, so the
    enumeration is deterministic. `optimistic` skips the checks on predicates that
    actions change (`where: blocks(s, t)`): false in one state, they may hold in a later
    one, so a reachability estimate must not rule those bindings out. With `reachable`
    (the atoms reachable from the state, ignoring deletes), a positive precondition on
    a changing predicate must be among them: such a binding could never run, and
    enumerating it would use up `limit` before the bindings that can (a sandwich made
    of bread already eaten). Then, too, the values that make these preconditions
    cheapest to reach are tried first (h_add, when `reachable` maps atoms to their
    costs; otherwise the values with which more of them hold now): with more bindings
    than `limit`, the one that can run soonest must not be cut (unstack(b9, b19) with b9
    on b19, where b9 sorts after b64; unstack(b92, b150) with b92 on b150 but not clear,
    beside 74 clear blocks that all tie on "one precondition holds now").
    """
    table = objects or Objects(task)
    refined = {p.name for p in template.parameters if p.refined}
    # The world answers for refined values, `where` included: checks on them are its own.
    checks = tuple(c for c in static_checks(task, template) if not refined & set(c.args))
    changing = task.domain.changed_predicates
    if optimistic:
        checks = tuple(c for c in checks if c.predicate not in changing)
    if not template.parameters and reachable is None:
        # nothing to bind (every action of a grounded domain): its checks are ground and
        # read once, as below, without the machinery (RoboWaiter's 174 actions: 1.0 ms
        # of its relaxed model's 3.6, now 0.45)
        if all(_holds(lit, partial, state) for lit in checks):
            yield dict(partial)
        return
    positive = tuple(c for c in checks if c.positive and c.predicate != EQUALITY)
    types = {p.name: p.type for p in template.parameters}
    hopes: tuple[Literal, ...] = ()
    if reachable is not None:
        hopes = tuple(
            p for p in template.preconditions
            if p.positive and p.predicate in changing and not refined & set(p.args))
    order = [p for p in template.parameters if p.name not in partial]
    # Enumerate ordinary parameters first: refiners usually need them bound.
    order.sort(key=lambda p: p.refined)
    # Each check is made once, right after the last of its parameters is bound.
    position = {p.name: i for i, p in enumerate(order)}
    staged: list[list[tuple[Literal, Container[Atom]]]] = [[] for _ in range(len(order) + 1)]
    for literal, facts in [*((c, state) for c in checks), *((h, reachable or ()) for h in hopes)]:
        due = max((position[a] for a in literal.args if a in position), default=-1)
        staged[due + 1].append((literal, facts))
    count = 0

    def options(binding: Mapping[str, str], parameter: Parameter) -> list[str]:
        if parameter.refined and refine is not None:
            return refine(template, binding, parameter)
        if parameter.refined:
            return list(table.of(parameter.type)) or [PLACEHOLDER]
        values = _supported(table, positive, binding, parameter.name, types, state)
        if isinstance(reachable, Mapping):
            return _cheapest_first(hopes, binding, parameter.name, types, reachable, values)
        return _now_first(table, hopes, binding, parameter.name, types, state, values)

    def extend(binding: dict[str, str], depth: int) -> Iterator[dict[str, str]]:
        nonlocal count
        if depth == len(order):
            count += 1
            yield dict(binding)
            return
        parameter = order[depth]
        due = staged[depth + 1]
        for value in options(binding, parameter):
            binding[parameter.name] = value
            if all(_holds(lit, binding, facts) for lit, facts in due):
                yield from extend(binding, depth + 1)
                if count >= limit:
                    del binding[parameter.name]
                    return
            del binding[parameter.name]

    start = dict(partial)
    if not all(_holds(lit, start, facts) for lit, facts in staged[0]):
        return
    yield from extend(start, 0)


def _supported(
    table: Objects,
    positive: tuple[Literal, ...],
    binding: Mapping[str, str],
    name: str,
    types: Mapping[str, str],
    state: frozenset[Atom],
) -> list[str]:
    """The objects for parameter `name` that some atom of each positive check allows.

    A check such as needs(p, q, r) is decidable only once q and r are both bound; read
    from the state's atoms, it already tells which q can work. This cuts the same values
    the staged checks would cut later, in the same order, without the cross product.
    """
    values = table.of(types[name])
    for literal in positive:
        if name not in literal.args:
            continue
        args = [binding.get(a, a if a not in types else None) for a in literal.args]
        if PLACEHOLDER in args:
            continue
        at = tuple(i for i, a in enumerate(literal.args) if a == name)
        allowed = table.values(state, literal.predicate, args, at)
        values = tuple(v for v in values if v in allowed)
    return list(values)


def _now_first(
    table: Objects,
    hopes: tuple[Literal, ...],
    binding: Mapping[str, str],
    name: str,
    types: Mapping[str, str],
    state: frozenset[Atom],
    values: list[str],
) -> list[str]:
    """`values`, those with which more preconditions hold in `state` first (stable).

    Only preconditions whose other parameters are already bound are read, from the
    state's atoms of their predicate, as `_supported` reads its checks.
    """
    holding: dict[str, int] = {}
    for literal in hopes:
        if name not in literal.args:
            continue
        args = [binding.get(a, a if a not in types else None) for a in literal.args]
        if any(want is None for a, want in zip(literal.args, args) if a != name):
            continue
        now: set[str] = set()
        for atom in table.atoms(state, literal.predicate):
            if len(atom.args) == len(args) and all(
                    a == name or want == got for a, want, got in zip(literal.args, args, atom.args)):
                seen = {got for a, got in zip(literal.args, atom.args) if a == name}
                if len(seen) == 1:
                    now |= seen
        for value in now:
            holding[value] = holding.get(value, 0) + 1
    if not holding:
        return values
    return sorted(values, key=lambda v: -holding.get(v, 0))


def _cheapest_first(
    hopes: tuple[Literal, ...],
    binding: Mapping[str, str],
    name: str,
    types: Mapping[str, str],
    costs: Mapping[Atom, float],
    values: list[str],
) -> list[str]:
    """`values`, cheapest first (stable): by the summed h_add cost of the preconditions
    that binding `name` to the value completes (0 for one that holds now).

    The ranking of achievers sorts by the same estimate, so the bindings the cap cuts
    are those ranking would have put last. Counting the preconditions that hold now
    cannot tell the block under a covered one (one holds, one is a step away) from
    every clear block elsewhere (one holds, one is out of reach for now).
    """
    relevant = []
    for literal in hopes:
        if name not in literal.args:
            continue
        if any(a != name and a in types and a not in binding for a in literal.args):
            continue
        relevant.append(literal)
    if not relevant:
        return values

    def cost(value: str) -> float:
        total = 0.0
        for literal in relevant:
            args = tuple([value if a == name else binding.get(a, a) for a in literal.args])
            total += costs.get(Atom(literal.predicate, args), math.inf)
        return total

    return sorted(values, key=cost)


def _holds(literal: Literal, binding: Mapping[str, str], facts: Container[Atom]) -> bool:
    """Whether a check holds under a binding that covers its parameters."""
    args = tuple([binding.get(a, a) for a in literal.args])
    if PLACEHOLDER in args:
        return True
    if literal.predicate == EQUALITY:
        return (args[0] == args[1]) is literal.positive
    return (Atom(literal.predicate, args) in facts) is literal.positive


def unify(
    task: Task, template: ActionTemplate, effect: Literal, atom: Atom,
    objects: Objects | None = None,
) -> dict[str, str] | None:
    """The partial binding under which `effect` becomes `atom`, or None if none does.

    Bound objects must have the parameter's type; `_` in an effect matches anything. A
    value that is no object of the task was named by the world (a pose it sampled for a
    refined parameter, now a condition `near(pose3)` to achieve) and is accepted.
    """
    if effect.predicate != atom.predicate or len(effect.args) != len(atom.args):
        return None
    table = objects or Objects(task)
    parameters = template.parameters
    binding: dict[str, str] = {}
    for name, value in zip(effect.args, atom.args):
        if name == "_":
            continue
        parameter: Parameter | None = None
        for declared in parameters:  # a handful: cheaper than a dict built per call
            if declared.name == name:
                parameter = declared
                break
        if parameter is None:
            if name != value:
                return None
            continue
        if binding.get(name, value) != value:
            return None
        if (not parameter.refined and not table.has_type(value, parameter.type)
                and value in task.object_types):
            return None  # a value the world refined (pose3) is not a task object: allowed
        binding[name] = value
    return binding


def wildcard_instances(literal: GroundLiteral, task: Task) -> list[GroundLiteral]:
    """A literal as plain ones: `not blocks(_, t)` is `not blocks(o, t)` for every object
    o of the task the wildcard can stand for (the predicate's parameter type)."""
    if WILDCARD not in literal.atom.args:
        return [literal]
    declared = task.domain.predicate_map[literal.atom.predicate].parameters
    choices = [task.objects_of(p.type) if a == WILDCARD else (a,)
               for a, p in zip(literal.atom.args, declared)]
    return [GroundLiteral(Atom(literal.atom.predicate, args), literal.positive)
            for args in itertools.product(*choices)]
