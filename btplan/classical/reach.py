"""Grounding the domain by relaxed reachability, as classical planners ground.

The relaxed model used to enumerate every binding that the static facts allow and then
let h_add find which of them can ever run: on parking that is 25,000 bindings, most of
the time of a 30 s budget. Here an action is instantiated only once every positive
precondition is an atom already reached from the initial state (deletes ignored), so
the bindings that can never run are never built. Each new atom is joined with the atoms
reached so far (semi-naive evaluation): it is unified with a precondition of its
predicate, and the other preconditions are matched one at a time, the one with most
arguments bound first (static ones on ties), through per-predicate hash indexes on the
bound argument positions. The actions found are the old model's actions that can run
in some relaxed state reached from the initial state, in the old model's order.
"""

from __future__ import annotations

from collections.abc import Iterator

from btplan.grounding import Objects
from btplan.model import EQUALITY, ActionTemplate, Atom, Literal, Task

Binding = dict[str, str]


class _Facts:
    """The atoms reached so far, by predicate, with hash indexes built on demand."""

    def __init__(self) -> None:
        self.seen: set[Atom] = set()
        self.of: dict[str, list[Atom]] = {}
        self._indexes: dict[str, dict[tuple[int, ...], dict[tuple[str, ...], list[Atom]]]] = {}

    def add(self, atom: Atom) -> bool:
        if atom in self.seen:
            return False
        self.seen.add(atom)
        self.of.setdefault(atom.predicate, []).append(atom)
        for positions, index in self._indexes.get(atom.predicate, {}).items():
            index.setdefault(tuple([atom.args[p] for p in positions]), []).append(atom)
        return True

    def matching(self, predicate: str, positions: tuple[int, ...],
                 values: tuple[str, ...]) -> list[Atom]:
        """The atoms of `predicate` whose arguments at `positions` are `values`."""
        if not positions:
            return self.of.get(predicate, [])
        by_positions = self._indexes.setdefault(predicate, {})
        index = by_positions.get(positions)
        if index is None:
            index = by_positions[positions] = {}
            for atom in self.of.get(predicate, []):
                index.setdefault(tuple([atom.args[p] for p in positions]), []).append(atom)
        return index.get(values, [])


class _Template:
    """One action template, split into what is joined and what is only checked."""

    def __init__(self, task: Task, template: ActionTemplate, table: Objects) -> None:
        self.template = template
        self.types = {p.name: p.type for p in template.parameters}
        self.table = table
        changing = task.domain.changed_predicates
        literals = [*template.preconditions,
                    *(c for c in template.constraints if c.predicate not in changing)]
        self.joins = [lit for lit in literals if lit.positive and lit.predicate != EQUALITY]
        self.static = [lit.predicate not in changing for lit in self.joins]
        # Checked once every parameter is bound: equalities and static negations (a
        # negation of a changing predicate may hold later; the relaxation ignores it).
        self.checks = [lit for lit in literals if lit.predicate == EQUALITY
                       or (not lit.positive and lit.predicate not in changing)]
        self.initial = task.initial_state

    def unify(self, literal: Literal, atom: Atom, binding: Binding) -> Binding | None:
        """`binding` extended so that `literal` becomes `atom`, or None."""
        if len(literal.args) != len(atom.args):
            return None
        out = binding
        for name, value in zip(literal.args, atom.args):
            kind = self.types.get(name)
            if kind is None:
                if name != value:
                    return None
                continue
            known = out.get(name)
            if known is None:
                if not self.table.has_type(value, kind):
                    return None
                if out is binding:
                    out = dict(binding)
                out[name] = value
            elif known != value:
                return None
        return out

    def join(self, facts: _Facts, binding: Binding, left: list[int]) -> Iterator[Binding]:
        """Every extension of `binding` under which the joins `left` are reached atoms."""
        if not left:
            yield from self._complete(binding)
            return
        best = max(left, key=lambda k: (self._bound(k, binding), self.static[k]))
        literal = self.joins[best]
        rest = [k for k in left if k != best]
        positions = tuple(i for i, a in enumerate(literal.args)
                          if a not in self.types or a in binding)
        values = tuple(binding.get(literal.args[i], literal.args[i]) for i in positions)
        for atom in list(facts.matching(literal.predicate, positions, values)):
            extended = self.unify(literal, atom, binding)
            if extended is not None:
                yield from self.join(facts, extended, rest)

    def _bound(self, k: int, binding: Binding) -> int:
        return sum(1 for a in self.joins[k].args if a not in self.types or a in binding)

    def _complete(self, binding: Binding) -> Iterator[Binding]:
        """Bind the parameters no join mentions to every object of their type."""
        free = [p for p in self.template.parameters if p.name not in binding]
        if not free:
            if self._checks_hold(binding):
                yield binding
            return
        first, extended = free[0], dict(binding)
        for value in self.table.of(first.type):
            extended[first.name] = value
            yield from self._complete(dict(extended))

    def _checks_hold(self, binding: Binding) -> bool:
        for lit in self.checks:
            args = tuple([binding.get(a, a) for a in lit.args])
            if lit.predicate == EQUALITY:
                holds = args[0] == args[1]
            else:
                holds = Atom(lit.predicate, args) in self.initial
            if holds is not lit.positive:
                return False
        return True

    def args(self, binding: Binding) -> tuple[str, ...]:
        return tuple(binding[p.name] for p in self.template.parameters)

    def adds(self, binding: Binding) -> list[Atom]:
        return [Atom(e.predicate, tuple([binding.get(a, a) for a in e.args]))
                for e in self.template.effects if e.positive]


def reachable_bindings(
    task: Task, objects: Objects | None = None
) -> list[tuple[ActionTemplate, tuple[str, ...]]] | None:
    """Every (template, arguments) whose positive preconditions are all reachable from the
    initial state ignoring deletes, ordered by template and then by arguments (the order
    in which binding enumerates them); None when some parameter is refined by a world,
    whose values no fixpoint over atoms can find."""
    if any(p.refined for t in task.domain.actions for p in t.parameters):
        return None
    table = objects or Objects(task)
    templates = [_Template(task, t, table) for t in task.domain.actions]
    by_predicate: dict[str, list[tuple[int, int]]] = {}
    for number, prepared in enumerate(templates):
        for k, literal in enumerate(prepared.joins):
            by_predicate.setdefault(literal.predicate, []).append((number, k))
    facts = _Facts()
    for atom in sorted(task.initial_state):
        facts.add(atom)
    found: set[tuple[int, tuple[str, ...]]] = set()
    queue: list[Atom] = []

    def record(number: int, bindings: Iterator[Binding]) -> None:
        prepared = templates[number]
        for binding in bindings:
            key = (number, prepared.args(binding))
            if key not in found:
                found.add(key)
                queue.extend(a for a in prepared.adds(binding) if facts.add(a))

    for number, prepared in enumerate(templates):
        record(number, prepared.join(facts, {}, list(range(len(prepared.joins)))))
    head = 0
    while head < len(queue):
        atom = queue[head]
        head += 1
        for number, k in by_predicate.get(atom.predicate, ()):
            prepared = templates[number]
            start = prepared.unify(prepared.joins[k], atom, {})
            if start is not None:
                rest = [j for j in range(len(prepared.joins)) if j != k]
                record(number, prepared.join(facts, start, rest))
    return [(task.domain.actions[n], args) for n, args in sorted(found)]
