"""The static part of achiever look-up, taken from the relaxed model instead of enumerated
on every expansion.

`grounding.bindings` enumerates an achiever's bindings afresh on every look-up, with
every check: the static ones (`where` constraints and preconditions on predicates no
action changes, read from the state) and those that depend on the state (`where`
constraints on changing predicates; with `prune_bindings`, positive preconditions that
must be reachable). While the state's static facts are the initial state's, the static
checks give the same answer on every look-up, and the relaxed model has already
enumerated, once per task, every grounding that passes them. A look-up takes the
groundings whose effect makes the condition, from an index by the values the effect
fixes, and applies only the checks that depend on the state.

The answer is the same set of bindings `bindings` yields, and achievers are ranked by a
total order afterwards, so the order they are found in does not matter, with one
exception: `bindings` stops after `limit` bindings, and which ones it keeps then
depends on its order. Such a look-up is left to `bindings` (`lookup` says None), as is
one of a template whose values a world refines or whose cost depends on its binding
(the relaxed model keeps only groundings of finite cost), one naming a value the task
does not know, and every look-up once the state's static facts differ from the
initial state's.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Container, Mapping, Sequence

from btplan.model import EQUALITY, ActionTemplate, Atom, GroundAction, GroundLiteral, Literal, Task
from btplan.grounding import Objects, unify

TABLE_LIMIT = 50_000
"""Groundings of one template beyond which it is not tabled. Well below the relaxed
model's own limit per template (200,000), so a tabled template was never cut short."""


class _Entry:
    """One grounding that the static checks allow, with the checks that depend on the state."""

    __slots__ = ("action", "checks", "hopes")

    def __init__(self, action: GroundAction, checks: tuple[tuple[Atom, bool], ...],
                 hopes: tuple[Atom, ...]) -> None:
        self.action = action
        self.checks = checks
        """`where` constraints on changing predicates, ground: (atom, whether it must hold)."""
        self.hopes = hopes
        """Positive preconditions on changing predicates: reachable, or never runnable."""


class _Table:
    """The statically allowed groundings of one template, indexed by effect on first use."""

    def __init__(self, template: ActionTemplate, entries: list[_Entry]) -> None:
        self.entries = entries
        self._names = [p.name for p in template.parameters]
        self._by_effect: dict[int, dict[tuple[str, ...], list[_Entry]]] = {}

    def matching(self, effect: int, partial: Mapping[str, str]) -> list[_Entry]:
        """The entries that agree with `partial` (the binding effect number `effect`
        unified to: it binds the same parameters whatever the condition)."""
        names = sorted(partial)
        index = self._by_effect.get(effect)
        if index is None:
            position = [self._names.index(n) for n in names]
            index = self._by_effect[effect] = {}
            for entry in self.entries:
                args = entry.action.args
                index.setdefault(tuple([args[i] for i in position]), []).append(entry)
        return index.get(tuple([partial[n] for n in names]), [])


Partials = dict[GroundLiteral, list[tuple[ActionTemplate, int, dict[str, str]]]]
"""Per condition, the effects (template, effect number) unifying with it, and how."""


class Way:
    """One effect of one template unified with a condition: a way to make it hold."""

    __slots__ = ("entries", "makes", "number", "partial", "tabled", "template")

    def __init__(self, template: ActionTemplate, number: int, partial: dict[str, str]) -> None:
        self.template = template
        self.number = number
        """Which of the template's effects."""
        self.partial = partial
        self.tabled: bool | None = None
        """Whether the table answers for it; None until first asked."""
        self.entries: list[_Entry] = []
        self.makes: list[bool] = []
        """Per entry, whether its action makes the condition true (`makes_true`)."""


class StaticBindings:
    """Per template, the groundings its static checks allow; per condition, its ways."""

    def __init__(self, task: Task, objects: Objects) -> None:
        self.task = task
        self.objects = objects
        self._changing = task.domain.changed_predicates
        self._static = self._static_part(task.initial_state)
        self._tables: Tables | None = None
        self._ways: dict[GroundLiteral, list[Way]] = {}
        self._state: frozenset[Atom] | None = None
        self._state_ok = False

    def ways(self, condition: GroundLiteral,
             effects: Sequence[tuple[ActionTemplate, int, Literal]],
             kept: Partials | None = None,
             store: dict[GroundLiteral, list[Way]] | None = None) -> list[Way]:
        """The effects that unify with `condition` (grounding.unify), worked out once.

        `kept`: the unifications of earlier tasks with the same objects and types, for
        the same `effects` of each condition (the domain's index), by condition: they
        depend on nothing else, and a planning call on a kept domain finds them.
        `store`: where the ways are kept instead of here, with the tables `pick` reads
        them from (a way, once asked, holds what its table answered)."""
        ways = self._ways if store is None else store
        found = ways.get(condition)
        if found is None:
            partials = None if kept is None else kept.get(condition)
            if partials is None:
                partials = []
                for template, number, effect in effects:
                    partial = unify(self.task, template, effect, condition.atom, self.objects)
                    if partial is not None:
                        partials.append((template, number, partial))
                if kept is not None:
                    kept[condition] = partials
            found = ways[condition] = [Way(*made) for made in partials]
        return found

    def _static_part(self, state: frozenset[Atom]) -> frozenset[Atom]:
        changing = self._changing
        return frozenset([a for a in state if a.predicate not in changing])

    def _usable(self, state: frozenset[Atom]) -> bool:
        """Whether `state` has the initial state's static facts (remembered for the
        last state asked about).

        The next state asked about differs from the last by a few atoms: when none of
        them is static, its static part is the last one's, and so is the answer. The
        difference is taken in C; only a static atom in it sends the check over the
        whole state again."""
        last = self._state
        if state is last:
            return self._state_ok
        self._state = state
        if last is not None:
            changing = self._changing
            if all(a.predicate in changing for a in state.symmetric_difference(last)):
                return self._state_ok
        self._state_ok = self._static_part(state) == self._static
        return self._state_ok

    def pick(
        self, way: Way, state: frozenset[Atom], reachable: Container[Atom] | None, limit: int,
        grounded: Sequence[GroundAction], makes_true: Callable[[GroundAction], bool],
        tables: Tables | None = None,
    ) -> list[GroundAction] | None:
        """The groundings that `bindings` would yield for `way` and that make its
        condition true, in no particular order; None when only `bindings` can tell (see
        the module docstring). `grounded` is the relaxed model's list of groundings, read
        when a template is first tabled; `makes_true` is asked once per grounding.
        `tables`: those kept with that relaxed model, if any (made here otherwise)."""
        if way.tabled is None:
            if tables is None:
                if self._tables is None:
                    self._tables = Tables(grounded, self._changing)
                tables = self._tables
            self._prepare(way, tables, makes_true)
        if not way.tabled or not self._usable(state):
            return None  # whether it is tabled does not depend on the state: asked first
        found: list[GroundAction] = []
        count = 0
        reached = reachable.__contains__ if reachable is not None else None
        for entry, makes in zip(way.entries, way.makes):
            if entry.checks and any((atom in state) is not positive
                                    for atom, positive in entry.checks):
                continue
            if reached is not None and entry.hopes and not all(map(reached, entry.hopes)):
                continue
            count += 1
            if count > limit:
                return None
            if makes:
                found.append(entry.action)
        return found

    def _prepare(self, way: Way, tables: Tables,
                 makes_true: Callable[[GroundAction], bool]) -> None:
        known = self.task.object_types
        table = tables.table(way.template)
        way.tabled = table is not None and all(v in known for v in way.partial.values())
        if table is not None and way.tabled:
            way.entries = table.matching(way.number, way.partial)
            way.makes = [makes_true(entry.action) for entry in way.entries]


class Tables:
    """Each template's statically allowed groundings, from one list of groundings.

    A table depends on nothing but its template, the predicates the domain changes and
    the list; the list is a relaxed model's, which is kept for later planning calls on
    the domain (reuse.py), and so are these tables with it: a RoboWaiter goal's call
    built its tables anew, a sixth of its time. Made on first use, template by template.
    """

    def __init__(self, grounded: Sequence[GroundAction], changing: Container[str]) -> None:
        self._grounded = grounded
        self._changing = changing
        self._tables: dict[str, _Table | None] = {}
        self._by_name: dict[str, list[GroundAction]] | None = None

    def table(self, template: ActionTemplate) -> _Table | None:
        """The template's table; None when it is not tabled (see the module docstring)."""
        name = template.name
        if name not in self._tables:
            self._tables[name] = self._build(template)
        return self._tables[name]

    def _build(self, template: ActionTemplate) -> _Table | None:
        if any(p.refined for p in template.parameters):
            return None  # the world answers for refined values, in the state it is in
        if template.cost_term is not None or template.cost == math.inf:
            return None  # groundings of infinite cost are not in the relaxed model
        changing = self._changing
        where = [c for c in template.constraints
                 if c.predicate != EQUALITY and c.predicate in changing]
        if self._by_name is None:
            self._by_name = {}
            for action in self._grounded:
                self._by_name.setdefault(action.name, []).append(action)
        mine = self._by_name.get(template.name, [])
        if len(mine) > TABLE_LIMIT:
            return None
        names = [p.name for p in template.parameters]
        entries: list[_Entry] = []
        for action in mine:
            checks: tuple[tuple[Atom, bool], ...] = ()
            if where:
                binding = dict(zip(names, action.args))
                checks = tuple((Atom(c.predicate, tuple([binding.get(a, a) for a in c.args])),
                                c.positive) for c in where)
            hopes = tuple([atom for atom in action.needs if atom.predicate in changing])
            entries.append(_Entry(action, checks, hopes))
        return _Table(template, entries)
