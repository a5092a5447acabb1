"""Mutex groups from lifted invariants: sets of atoms of which at most one ever holds.

h^2 (btplan/classical/mutex.py) finds every mutex pair but works on pairs of ground
atoms: a 200-block blocksworld has 40,000 atoms and 800 million pairs. Large tasks
use these groups instead, found on the action templates, as classical planners do
(Helmert 2009 calls them monotonicity invariants), at a cost independent of the
number of objects.

A pattern picks a predicate and its counted argument positions (all of them, or all
but one); a candidate is a few patterns with as many counted positions each. An
instance of a candidate fixes the counted arguments: on(b1, _), ontable(b1) and
holding(b1) are one instance of {on@0, ontable@0, holding@0}. The candidate is an
invariant when no instance holds two atoms initially and every action that adds an
atom of an instance also deletes one of the same instance that its preconditions
require (so it replaces the member that held, if any), and adds no two atoms to one
instance. Two different atoms that share an instance of an invariant never hold
together.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable

from btplan.model import EQUALITY, WILDCARD, ActionTemplate, Atom, Domain, Literal

Pattern = tuple[str, tuple[int, ...]]
"""(predicate, counted argument positions, ascending)."""

MAX_PATTERNS = 3
"""Patterns per candidate: the groups classic domains need have at most three."""


class MutexGroups:
    """The invariants of a domain that hold in one initial state, and their instances."""

    def __init__(self, domain: Domain, initial: Iterable[Atom]) -> None:
        init = list(initial)
        self.candidates = [c for c in _candidates(domain)
                           if _balanced(c, domain.actions) and _initially_fine(c, init)]
        self._by_predicate: dict[str, list[tuple[int, tuple[int, ...]]]] = {}
        for number, candidate in enumerate(self.candidates):
            for predicate, counted in candidate:
                self._by_predicate.setdefault(predicate, []).append((number, counted))
        self._instances: dict[Atom, frozenset[tuple[int, tuple[str, ...]]]] = {}

    def covers(self, atom: Atom) -> bool:
        """Whether some invariant speaks of `atom`'s predicate; the groups say nothing of an
        atom they do not cover (which is not to say it excludes nothing)."""
        return atom.predicate in self._by_predicate

    def instances(self, atom: Atom) -> frozenset[tuple[int, tuple[str, ...]]]:
        """The invariant instances `atom` belongs to, as (candidate number, counted arguments),
        remembered per atom: two different atoms that share one never hold together."""
        found = self._instances.get(atom)
        if found is None:
            found = self._instances[atom] = frozenset(
                (number, tuple(atom.args[i] for i in counted))
                for number, counted in self._by_predicate.get(atom.predicate, ()))
        return found

    def exclusive(self, a: Atom, b: Atom) -> bool:
        """True when both atoms are in one instance of an invariant (and differ)."""
        return a != b and not self.instances(a).isdisjoint(self.instances(b))


def _patterns(domain: Domain) -> list[Pattern]:
    found: list[Pattern] = []
    for predicate in domain.predicates:
        if predicate.name == EQUALITY:
            continue
        positions = tuple(range(predicate.arity))
        found.append((predicate.name, positions))
        for free in positions:
            found.append((predicate.name, tuple(p for p in positions if p != free)))
    return found


def _candidates(domain: Domain) -> list[frozenset[Pattern]]:
    """Sets of up to MAX_PATTERNS patterns of distinct predicates, equally many counted."""
    changed = domain.changed_predicates
    patterns = [p for p in _patterns(domain) if p[0] in changed]
    by_size: dict[int, list[Pattern]] = {}
    for pattern in patterns:
        by_size.setdefault(len(pattern[1]), []).append(pattern)
    found: list[frozenset[Pattern]] = []
    for group in by_size.values():
        for size in range(1, MAX_PATTERNS + 1):
            for chosen in itertools.combinations(group, size):
                if len({p[0] for p in chosen}) == size:
                    found.append(frozenset(chosen))
    return found


def _key(literal: Literal, counted: tuple[int, ...]) -> tuple[str, ...]:
    return tuple(literal.args[i] for i in counted)


def _balanced(candidate: frozenset[Pattern], actions: Iterable[ActionTemplate]) -> bool:
    """Whether every action keeps each instance at one atom at most (module docstring)."""
    counted = dict(candidate)
    for action in actions:
        required = {(p.predicate, p.args) for p in action.preconditions if p.positive}
        added = {(e.predicate, e.args) for e in action.effects if e.positive}
        # A delete counts when the atom surely held and does not come back (PDDL adds
        # after it deletes: deleting and adding one atom leaves it true).
        deletes = [e for e in action.effects
                   if not e.positive and e.predicate in counted and WILDCARD not in e.args
                   and (e.predicate, e.args) in required and (e.predicate, e.args) not in added]
        used: list[str] = []
        keys: list[tuple[str, ...]] = []
        for add in action.effects:
            if not add.positive or add.predicate not in counted:
                continue
            if (add.predicate, add.args) in required:
                continue  # it held already: nothing joins the instance
            key = _key(add, counted[add.predicate])
            match = next((d for d in deletes if _key(d, counted[d.predicate]) == key
                          and (d.predicate, d.args) != (add.predicate, add.args)), None)
            # Two adds must replace atoms of two different predicates: then, should their
            # instances coincide under some binding, the action needed two members of one
            # instance at once and cannot run.
            if match is None or key in keys or match.predicate in used:
                return False
            keys.append(key)
            used.append(match.predicate)
    return True


def _initially_fine(candidate: frozenset[Pattern], init: list[Atom]) -> bool:
    counted = dict(candidate)
    seen: set[tuple[str, ...]] = set()
    for atom in init:
        positions = counted.get(atom.predicate)
        if positions is None:
            continue
        key = tuple(atom.args[i] for i in positions)
        if key in seen:
            return False
        seen.add(key)
    return True
