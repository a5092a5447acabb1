"""Pairs of atoms that never hold together (h^2 reachability from the initial state).

The paper's conflict is "an effect of an earlier action is in conflict with a
condition of the new subtree". An earlier sibling in a Sequence is done while its
condition g holds, so what matters is whether the new subtree needs something that
cannot be true while g is: holding(cube) and hand_empty, on(a, b) and clear(b). Such
pairs are mutually exclusive, and h^2 (Haslum and Geffner, 2000) finds them: a pair is
reachable if some action adds one atom while the other holds with all its
preconditions; pairs never reached are mutexes. Rows are Python ints used as bit
sets, so the fixpoint stays fast without extra dependencies.

h^2 costs the square of the number of atoms in memory and more in time: beyond
H2_MAX_ATOMS atoms (a 40-block blocksworld has 1,700, a 100-block one 10,000), and
when the domain is given, the mutexes come from lifted invariants instead
(btplan/classical/invariants.py): fewer pairs, found at a cost that does not grow
with the number of objects.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Iterable, Sequence

from btplan.model import Atom, Domain, GroundAction, GroundLiteral, matches
from btplan.classical.invariants import MutexGroups
from btplan.collector import building

H2_MAX_ATOMS = 2000
"""Above this many atoms, and given the domain, mutexes come from invariants."""

WITNESS_ACTIONS = 500
"""Actions beyond which the states one action reaches from the initial state are not
looked at before the mutexes are computed (`Mutexes._together`)."""


class Mutexes:
    """h^2 mutexes over the atoms of a grounded domain (or invariant groups, when large)."""

    def __init__(self, actions: Sequence[GroundAction] | Callable[[], Sequence[GroundAction]],
                 initial: Iterable[Atom], domain: Domain | None = None,
                 h2_max_atoms: int = H2_MAX_ATOMS) -> None:
        """`actions` may be a function that gives them: then nothing is computed (nor
        are the actions asked for) until a question needs it, or `ready`. A plan of one
        expansion often asks none: its achiever has fewer than two preconditions, or
        they all hold initially, and no earlier sibling's condition is to be kept."""
        self._initial = frozenset(initial)
        self._domain, self._h2_max_atoms = domain, h2_max_atoms
        self._source = actions if callable(actions) else None
        self._actions = None if callable(actions) else actions
        self.groups: MutexGroups | None = None
        self._index: dict[Atom, int] = {}
        self._numbered = False
        self._rows: list[int] = []
        self._reached = 0
        self._built = False
        self._next: list[frozenset[Atom]] | None = None
        if not callable(actions):
            self._build()

    def ready(self) -> Mutexes:
        """Computed now, if they were not yet: for a caller that wants their cost paid
        before it starts (`btplan.acting.online.task_models`)."""
        if not self._built:
            self._build()
        return self

    @property
    def computed(self) -> bool:
        """Whether the fixpoint (or the invariant groups) is computed; until a question
        needs it, those asked so far were answered without."""
        return self._built

    def _given(self) -> Sequence[GroundAction]:
        """The actions, asked for once."""
        if self._actions is None:
            assert self._source is not None
            self._actions, self._source = self._source(), None
        return self._actions

    def _universe(self) -> dict[Atom, int]:
        """Every atom the initial state or an action mentions, numbered (once)."""
        if not self._numbered:
            self._numbered = True
            universe = self._index
            for atom in sorted(self._initial):
                universe.setdefault(atom, len(universe))
            for action in self._given():
                for atom in [*(p.atom for p in action.preconditions), *action.add,
                             *action.delete]:
                    universe.setdefault(atom, len(universe))
        return self._index

    def _build(self) -> None:
        self._built = True
        with building():
            universe = self._universe()
            actions = self._given()
            self._actions, self._next = None, None  # not needed once built
            domain, self._domain = self._domain, None  # mutexes kept with a domain: no
            # reference back to it once built
            init = sorted(self._initial)
            if domain is not None and len(universe) > self._h2_max_atoms:
                self.groups = MutexGroups(domain, init)
                return
            atoms = list(universe)
            self._rows = [0] * len(atoms)
            start = 0
            for atom in init:
                start |= 1 << universe[atom]
            for atom in init:
                self._rows[universe[atom]] = start
            self._reached = start
            self._fixpoint(actions, atoms)

    def _together(self, atoms: Collection[Atom]) -> bool:
        """Whether the atoms all hold in the initial state, or all in a state one action
        reaches from it, so that no two of them exclude each other; nothing else need be
        computed to say so. h^2 starts from the initial state's pairs and reaches those
        of every such state (it fires an action whose positive preconditions hold
        pairwise), and no invariant group holds two atoms of the initial state; the
        states one action reaches are only looked at where h^2, not the groups, would
        answer, and the actions are few (WITNESS_ACTIONS). So a goal of two steps, the
        robot to move and then the object to pick, is ranked without the fixpoint."""
        if self._initial.issuperset(atoms):
            return True
        if self._next is None:
            self._next = self._one_step()
        return any(state.issuperset(atoms) for state in self._next)

    def _by_h2(self) -> bool:
        """Whether h^2 answers (not invariant groups), before it is computed."""
        return self._domain is None or len(self._universe()) <= self._h2_max_atoms

    def _pairs_together(self, needs: Sequence[GroundLiteral],
                        held: Sequence[GroundLiteral]) -> bool:
        """Whether no need is the negation of a held condition and each positive need
        holds `_together` with each positive held condition h^2 knows of: then `screen`
        finds no need excluded, with no fixpoint (a robot's move planned ahead of its
        hand, which stays empty)."""
        universe = self._universe()
        for atom, positive in needs:
            for hold in held:
                if hold.atom == atom:
                    if hold.positive != positive:
                        return False
                elif (positive and hold.positive and atom in universe
                      and hold.atom in universe and not self._together((hold.atom, atom))):
                    return False
        return True

    def _one_step(self) -> list[frozenset[Atom]]:
        """The states one action reaches from the initial state (none looked at where
        the actions are many or invariant groups would stand in for h^2)."""
        actions = self._given()
        if len(actions) > WITNESS_ACTIONS or not self._by_h2():
            return []
        initial = self._initial
        return [action.apply(initial) for action in actions if action.applicable(initial)]

    def _fixpoint(self, actions: Sequence[GroundAction], atoms: list[Atom]) -> None:
        index = self._index
        by_predicate: dict[str, list[Atom]] = {}
        for atom in atoms:
            by_predicate.setdefault(atom.predicate, []).append(atom)
        compiled = []
        for action in actions:
            pre = [index[p.atom] for p in action.preconditions if p.positive]
            add = [index[a] for a in action.add]
            deleted = 0
            for atom in action.delete:
                deleted |= 1 << index[atom]
            for pattern in action.delete_patterns:
                for atom in by_predicate.get(pattern.predicate, ()):
                    if matches(pattern, atom):
                        deleted |= 1 << index[atom]
            add_bits = 0
            for i in add:
                add_bits |= 1 << i
            pre_bits = 0
            for i in pre:
                pre_bits |= 1 << i
            compiled.append((pre, pre_bits, add, add_bits, deleted & ~add_bits))
        rows = self._rows
        # Pairs are symmetric: when atom q gains partners, each partner gains q. Setting
        # those bits one by one in big ints copies a whole row per bit (quadratic in the
        # number of atoms), so they are set in a byte array per row and merged into the
        # row the next time it is read.
        size = (len(atoms) + 7) // 8
        pending = [bytearray(size) for _ in atoms]
        dirty = [False] * len(atoms)

        def row(i: int) -> int:
            if dirty[i]:
                rows[i] |= int.from_bytes(pending[i], "little")
                dirty[i] = False
            return rows[i]

        changed = True
        while changed:
            changed = False
            for pre, pre_bits, add, add_bits, deleted in compiled:
                together = self._reached
                if together & pre_bits != pre_bits:
                    continue  # a precondition is not reachable yet
                for i in pre:
                    together &= rows[i] if not dirty[i] else row(i)
                if together & pre_bits != pre_bits:
                    continue  # a pair of preconditions is not reachable yet
                keep = together & ~deleted & ~add_bits
                for q in add:
                    new = (keep | add_bits) & ~(rows[q] if not dirty[q] else row(q))
                    if not new:
                        continue
                    changed = True
                    rows[q] |= new
                    self._reached |= 1 << q
                    byte, bit = q >> 3, 1 << (q & 7)
                    bits = bin(new)[:1:-1]  # least significant first
                    i = bits.find("1")
                    while i >= 0:
                        if i != q:
                            pending[i][byte] |= bit
                            dirty[i] = True
                        i = bits.find("1", i + 1)
        for i in range(len(atoms)):
            row(i)

    def knows(self, atom: Atom) -> bool:
        """Whether these mutexes can judge `atom`: it is one of the grounded atoms and, with
        invariant groups, a covered one. Callers judge an unknown atom another way (as a
        threat from the actions)."""
        if not self._built:
            if self._by_h2():
                return atom in self._universe()  # h^2 knows every atom it numbers
            self._build()
        if self.groups is not None:
            return atom in self._index and self.groups.covers(atom)
        return atom in self._index

    def unreachable(self, atom: Atom) -> bool:
        """True when h^2 proves `atom` never holds (never when invariants stand in for h^2)."""
        if not self._built:
            self._build()
        if self.groups is not None:
            return False
        i = self._index.get(atom)
        return i is not None and not self._reached >> i & 1

    def any_exclusive(self, atoms: Sequence[Atom]) -> bool:
        """Whether two of `atoms` (as positive literals) are `exclusive`, all pairs
        asked at once: one bit test per atom against the others instead of a call per
        pair (ranking asks it of every new achiever's preconditions)."""
        if not self._built:
            if len(set(atoms)) < 2 or self._together(atoms):
                return False
            self._build()
        if self.groups is not None:
            known = [GroundLiteral(a) for a in atoms if self.knows(a)]
            return any(self.exclusive(a, b) for i, a in enumerate(known) for b in known[i + 1:])
        index, reached, rows = self._index, self._reached, self._rows
        mine = 0
        for atom in atoms:
            i = index.get(atom)
            if i is not None and reached >> i & 1:
                mine |= 1 << i
        for atom in atoms:
            i = index.get(atom)
            if i is not None and mine >> i & 1 and mine & ~rows[i] & ~(1 << i):
                return True  # rows are symmetric: row i tells of every pair with i
        return False

    def screen(self, needs: Sequence[GroundLiteral], held: Sequence[GroundLiteral]
               ) -> tuple[bool, list[GroundLiteral]]:
        """Whether some need that it `knows` cannot hold while the `held` conditions do
        (`exclusive` with one of them), looking at the needs in order; and the needs
        before that one, or all, that it does not know (for the caller to judge another
        way). Conflict checks ask it of each way a new subtree can succeed against each
        earlier sibling: one call where there were two per need."""
        if not self._built:
            if self._by_h2() and self._pairs_together(needs, held):
                universe = self._universe()
                return False, [need for need in needs if need.atom not in universe]
            self._build()
        unknown: list[GroundLiteral] = []
        if self.groups is not None:
            for need in needs:
                if not self.knows(need.atom):
                    unknown.append(need)
                elif any(self.exclusive(hold, need) for hold in held):
                    return True, unknown
            return False, unknown
        index, reached, rows = self._index, self._reached, self._rows
        for need in needs:
            atom, positive = need
            j = index.get(atom)
            if j is None:
                unknown.append(need)
                continue
            if not positive or not reached >> j & 1:
                j = -1  # only its own negation excludes it
            for hold in held:
                if hold.atom == atom:
                    if hold.positive != positive:
                        return True, unknown
                elif j >= 0 and hold.positive:
                    i = index.get(hold.atom)
                    if i is not None and reached >> i & 1 and not rows[i] >> j & 1:
                        return True, unknown
        return False, unknown

    def exclusive(self, a: GroundLiteral, b: GroundLiteral) -> bool:
        """True when `a` and `b` can never hold at the same time (as far as h^2 sees)."""
        if a.atom == b.atom:
            return a.positive != b.positive
        if not (a.positive and b.positive):
            return False
        if not self._built:
            if self._together((a.atom, b.atom)):
                return False
            self._build()
        if self.groups is not None:
            return self.groups.exclusive(a.atom, b.atom)
        i, j = self._index.get(a.atom), self._index.get(b.atom)
        if i is None or j is None:
            return False
        if not (self._reached >> i & 1 and self._reached >> j & 1):
            return False
        return not self._rows[i] >> j & 1
