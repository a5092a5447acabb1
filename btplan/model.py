"""The planning models every layer shares: domains, problems and their grounded forms.

Both input languages (btplan's own and PDDL) produce these models, so everything
downstream works on either. They are frozen so that a parsed domain can be shared
and cached safely. Grounded atoms are plain named tuples: the planner and the
worlds hash and compare millions of them, and a tuple does that at C speed.

This module imports nothing else from btplan but its record classes (btplan/records.py)
and the grounded atoms (btplan/atoms.py).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from functools import cached_property

from btplan.atoms import WILDCARD as WILDCARD
from btplan.atoms import Atom as Atom
from btplan.atoms import GroundLiteral as GroundLiteral
from btplan.atoms import matches as matches
from btplan.records import build, dataclass_transform, replace

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, Self

ROOT_TYPE = "object"
"""Every type without a declared parent derives from this one."""

EQUALITY = "="
"""The built-in predicate of `a == b` (and, negated, `a != b`)."""


@dataclass_transform(kw_only_default=True, frozen_default=True)
class Frozen:
    """Base of the models: immutable, built by keyword, strict about unknown fields.

    Plain frozen records rather than a validation library: the readers check their
    input before they build a model, and importing and building validated models cost
    more than a whole small planning run (`btplan plan` starts in a fraction of a second).
    Every subclass becomes a keyword-only frozen record, a dataclass without the cost of
    compiling its methods at import (btplan/records.py); lists given for tuple fields
    are stored as tuples so that models stay hashable.
    """

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        build(cls, frozen=True, slots=False, kw_only=True)

    def __post_init__(self) -> None:
        for name, value in vars(self).items():
            if isinstance(value, list):
                object.__setattr__(self, name, tuple(value))

    def model_copy(self, *, update: Mapping[str, Any] | None = None) -> Self:
        """A new model with some fields changed (cached properties are recomputed)."""
        return replace(self, **(update or {}))


class TypeDef(Frozen):
    """A declared type; `parent` is None only for the root type."""

    name: str
    parent: str | None = ROOT_TYPE


class TypedName(Frozen):
    """An object or constant with its type."""

    name: str
    type: str = ROOT_TYPE


class Parameter(Frozen):
    """A typed parameter of a predicate or action template.

    A `refined` parameter is not chosen by the planner among the objects: the world
    backend supplies it (a trajectory, a grasp pose), as the paper's RefineActions does.
    """

    name: str
    type: str = ROOT_TYPE
    refined: bool = False


class Predicate(Frozen):
    """A predicate of the domain: its name and typed parameters."""

    name: str
    parameters: tuple[Parameter, ...] = ()

    @property
    def arity(self) -> int:
        """How many arguments the predicate takes."""
        return len(self.parameters)


class Literal(Frozen):
    """A possibly negated atom whose arguments are parameter names or constants."""

    predicate: str
    args: tuple[str, ...] = ()
    positive: bool = True

    def __str__(self) -> str:
        if self.predicate == EQUALITY:
            op = "==" if self.positive else "!="
            return f"{self.args[0]} {op} {self.args[1]}"
        text = f"{self.predicate}({', '.join(self.args)})"
        return text if self.positive else f"not {text}"


class ActionTemplate(Frozen):
    """An action template with its pre- and postconditions (the paper's Table I).

    `constraints` ("where" in the language) restrict the bindings of parameters but are
    not conditions the tree checks at run time: static relations such as which
    trajectory leads where, and equalities. `duration` is in ticks of the symbolic world.
    """

    name: str
    parameters: tuple[Parameter, ...] = ()
    constraints: tuple[Literal, ...] = ()
    preconditions: tuple[Literal, ...] = ()
    effects: tuple[Literal, ...] = ()
    cost: float = 1.0
    cost_term: Literal | None = None
    """When set, the cost is this static function's value under the binding, as in PDDL's
    `(increase (total-cost) (road-length ?from ?to))`; `cost` is then unused."""
    duration: int = 1

    @property
    def add_effects(self) -> tuple[Literal, ...]:
        """The effects that make something true."""
        return tuple(e for e in self.effects if e.positive)

    @property
    def delete_effects(self) -> tuple[Literal, ...]:
        """The effects that make something false (`not near(_)` included)."""
        return tuple(e for e in self.effects if not e.positive)


class Domain(Frozen):
    """A planning domain: types, constants, predicates, action templates, cost functions."""

    name: str
    requirements: tuple[str, ...] = ()
    types: tuple[TypeDef, ...] = (TypeDef(name=ROOT_TYPE, parent=None),)
    constants: tuple[TypedName, ...] = ()
    predicates: tuple[Predicate, ...] = ()
    actions: tuple[ActionTemplate, ...] = ()
    functions: tuple[Predicate, ...] = ()
    """Static numeric functions that give action costs (PDDL's `:action-costs`)."""

    @property
    def has_costs(self) -> bool:
        """Whether plan cost is the sum of action costs rather than the plan's length."""
        return ":action-costs" in self.requirements or any(
            a.cost != 1.0 or a.cost_term is not None for a in self.actions)

    @cached_property
    def type_parents(self) -> Mapping[str, str | None]:
        """Each type's parent (None for the root)."""
        return {t.name: t.parent for t in self.types}

    @cached_property
    def predicate_map(self) -> Mapping[str, Predicate]:
        """The predicates by name."""
        return {p.name: p for p in self.predicates}

    @cached_property
    def predicate_ports(self) -> Mapping[str, tuple[str, ...]]:
        """Each predicate's parameter names: the ports of its tree leaves (made often)."""
        return {p.name: tuple(q.name for q in p.parameters) for p in self.predicates}

    @cached_property
    def action_map(self) -> Mapping[str, ActionTemplate]:
        """The action templates by name."""
        return {a.name: a for a in self.actions}

    def ancestors(self, type_name: str) -> tuple[str, ...]:
        """The type itself, then its parents up to the root."""
        chain: list[str] = []
        current: str | None = type_name
        while current is not None and current not in chain:
            chain.append(current)
            current = self.type_parents.get(current)
        return tuple(chain)

    def is_subtype(self, type_name: str, of: str) -> bool:
        """Whether `type_name` is `of` or one of its descendants."""
        return of in self.ancestors(type_name)

    @cached_property
    def changed_predicates(self) -> frozenset[str]:
        """Predicates some action can make true or false; the others are static."""
        return frozenset(e.predicate for a in self.actions for e in a.effects)

    @cached_property
    def kept(self) -> dict[str, Any]:
        """What other layers work out from this domain and keep with it for later use
        (the planner's grounded models, btplan/planner/reuse.py): the domain is frozen,
        so what is kept stays right, and it goes when the domain does."""
        return {}


class FunctionValue(Frozen):
    """The value of a static numeric function in a problem: `(= (road-length a b) 12)`."""

    function: str
    args: tuple[str, ...] = ()
    value: float


class Problem(Frozen):
    """Objects, initial facts and goal conditions; the goal is ground literals."""

    name: str
    domain: str
    objects: tuple[TypedName, ...] = ()
    init: tuple[Literal, ...] = ()
    goal: tuple[Literal, ...] = ()
    values: tuple[FunctionValue, ...] = ()


class Task(Frozen):
    """A domain together with one of its problems: what planning and acting need."""

    domain: Domain
    problem: Problem

    @cached_property
    def object_types(self) -> Mapping[str, str]:
        """Every object and constant name mapped to its declared type."""
        table = {c.name: c.type for c in self.domain.constants}
        table.update({o.name: o.type for o in self.problem.objects})
        return table

    def objects_of(self, type_name: str) -> tuple[str, ...]:
        """Objects whose type is `type_name` or one of its subtypes, sorted by name."""
        return tuple(
            sorted(n for n, t in self.object_types.items() if self.domain.is_subtype(t, type_name))
        )

    @cached_property
    def initial_state(self) -> frozenset[Atom]:
        """The problem's initial facts as atoms."""
        return frozenset(Atom(lit.predicate, lit.args) for lit in self.problem.init)

    @cached_property
    def goal_literals(self) -> tuple[GroundLiteral, ...]:
        """The goal's conditions, grounded (negated ones included)."""
        return tuple(GroundLiteral(Atom(g.predicate, g.args), g.positive) for g in self.problem.goal)

    @cached_property
    def function_values(self) -> Mapping[Atom, float]:
        """Static numeric functions (action costs) by their ground term."""
        return {Atom(v.function, v.args): v.value for v in self.problem.values}

    def instantiate(self, template: ActionTemplate, args: tuple[str, ...]) -> GroundAction:
        """`instantiate` with this problem's action costs, its atoms and literals shared."""
        return instantiate(template, args, self.function_values, self.interned)

    @cached_property
    def interned(self) -> dict[Atom | GroundLiteral, Any]:
        """One object for each atom and literal the task's groundings mention.

        A problem's tens of thousands of groundings name the same few hundred atoms
        (parking p04: 32,856 groundings, 266,000 literals, 949 atoms): made anew for each
        grounding, the atoms and literals took two thirds of the grounded model's memory.
        """
        return {}


# --- grounded forms -------------------------------------------------------------------------


class GroundAction(Frozen):
    """An action template with every parameter bound to an object or a refined value.

    `delete_patterns` hold negative effects with wildcards (`not near(_)`); they delete
    every matching atom before `add` is applied, which is how a state variable such
    as the robot's position is written in STRIPS terms.
    """

    name: str
    args: tuple[str, ...] = ()
    port_names: tuple[str, ...] = ()
    preconditions: tuple[GroundLiteral, ...] = ()
    add: tuple[Atom, ...] = ()
    delete: tuple[Atom, ...] = ()
    delete_patterns: tuple[Atom, ...] = ()
    cost: float = 1.0
    duration: int = 1

    @cached_property
    def key(self) -> tuple[str, tuple[str, ...]]:
        """(name, args): made once per action, read as a plain attribute after (planning
        keys its tables by it on every expansion)."""
        return (self.name, self.args)

    @cached_property
    def needs(self) -> tuple[Atom, ...]:
        """The positive preconditions' atoms, in order (one written twice, twice).

        Taken apart once per action: the relaxed model, ranking, the relaxed plan and
        the look-ahead all read them, from the same grounded actions."""
        return tuple([p.atom for p in self.preconditions if p.positive])

    def applicable(self, state: frozenset[Atom] | set[Atom]) -> bool:
        """Whether every precondition holds in `state`."""
        return all(p.holds(state) for p in self.preconditions)

    def achieved(self, state: frozenset[Atom] | set[Atom]) -> bool:
        """Whether `state` already shows every effect (adds there, plain deletes gone)."""
        return all(a in state for a in self.add) and not any(
            a in state for a in self.delete if a not in self.add)

    def deletes(self, atom: Atom) -> bool:
        """True when applying this action makes `atom` false (unless it also adds it)."""
        if atom in self.add:
            return False
        if atom in self.delete:
            return True
        return bool(self.delete_patterns) and self._pattern_hit(atom)

    def apply(self, state: frozenset[Atom]) -> frozenset[Atom]:
        """Delete first, then add: an effect list `not near(_), near(x)` ends with near(x)."""
        kept = state.difference(self.delete) if self.delete else state
        if self.delete_patterns:
            kept = frozenset(a for a in kept if not self._pattern_hit(a))
        return kept.union(self.add)

    def _pattern_hit(self, atom: Atom) -> bool:
        return any(matches(p, atom) for p in self.delete_patterns)

    def __str__(self) -> str:
        return f"{self.name}({', '.join(self.args)})"

    def ipc(self) -> str:
        """The IPC plan-file form, lower case: `(pick cube table)`."""
        return "(" + " ".join([self.name, *self.args]).lower() + ")"


def atoms(items: Iterable[tuple[str, tuple[str, ...]]]) -> frozenset[Atom]:
    """Build a state from (predicate, args) pairs; a convenience for tests and worlds."""
    return frozenset(Atom(p, tuple(a)) for p, a in items)


def ground_literal(literal: Literal, binding: Mapping[str, str],
                   interned: dict[Any, Any] | None = None) -> GroundLiteral:
    """Replace parameter names by their objects; constants and `_` stay as they are.

    With `interned` (Task.interned), an equal literal made before is returned instead,
    and a new one shares the atom made before."""
    get = binding.get
    args = tuple([get(a, a) for a in literal.args])
    made = GroundLiteral(Atom(literal.predicate, args), literal.positive)
    if interned is None:
        return made
    found: GroundLiteral | None = interned.get(made)
    if found is None:
        atom = interned.setdefault(made.atom, made.atom)
        found = made if atom is made.atom else GroundLiteral(atom, made.positive)
        interned[found] = found
    return found


def instantiate(
    template: ActionTemplate, args: tuple[str, ...], values: Mapping[Atom, float] | None = None,
    interned: dict[Any, Any] | None = None,
) -> GroundAction:
    """Ground `template` with `args` given in parameter order.

    Equalities are binding constraints, not run-time conditions, so they are left out of
    the preconditions whether they were written under `where` or under `pre`. A cost
    given by a function takes its value from `values`; an undefined value makes the
    action unusable (infinite cost), as PDDL makes it inapplicable. `interned`: see
    `ground_literal`.
    """
    if len(args) != len(template.parameters):
        raise ValueError(f"{template.name} takes {len(template.parameters)} arguments, got {len(args)}")
    binding = {p.name: a for p, a in zip(template.parameters, args)}
    # ground_literal, written out: a relaxed model grounds every action of the domain,
    # and the calls and the literals of effects made it twice as slow (RoboWaiter's 174
    # actions of about 30 effects each: 2.4 ms, now 1.3; bench/fixed_cost.py). With
    # `interned`, each atom and literal is the one made before, when there was one.
    get = binding.get
    if interned is None:
        pre = tuple([
            GroundLiteral(Atom(lit.predicate, tuple([get(a, a) for a in lit.args]) if binding
                               else lit.args), lit.positive)
            for lit in template.preconditions if lit.predicate != EQUALITY])
    else:
        pre = tuple([ground_literal(lit, binding, interned) for lit in template.preconditions
                     if lit.predicate != EQUALITY])
    add: list[Atom] = []
    delete: list[Atom] = []
    patterns: list[Atom] = []
    for effect in template.effects:
        if interned is None:
            atom = Atom(effect.predicate,
                        tuple([get(a, a) for a in effect.args]) if binding else effect.args)
        else:
            atom = ground_literal(effect, binding, interned).atom
        if effect.positive:
            add.append(atom)
        elif WILDCARD in atom.args:
            patterns.append(atom)
        else:
            delete.append(atom)
    return GroundAction(
        name=template.name,
        args=tuple(args),
        port_names=tuple(p.name for p in template.parameters),
        preconditions=pre,
        add=tuple(add),
        delete=tuple(delete),
        delete_patterns=tuple(patterns),
        cost=_cost(template, binding, values),
        duration=template.duration,
    )


def _cost(
    template: ActionTemplate, binding: Mapping[str, str], values: Mapping[Atom, float] | None
) -> float:
    term = template.cost_term
    if term is None:
        return template.cost
    atom = ground_literal(term, binding).atom
    return (values or {}).get(atom, math.inf)
