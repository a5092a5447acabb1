"""Grounded actions over integer-encoded states, for the last-resort search.

A search looks at many thousands of states; as sets of atoms each costs kilobytes and
every precondition test hashes atoms. Here an atom is a bit, a state one Python int:
applying an action is two bit operations, a state is hashed as one number, and the
relaxed exploration of h_FF runs over lists indexed by atom numbers. Only the atoms
that some action reads or writes get a bit (the others never change and no action
tests them), and atoms a start state brings that no action knows are ignored the same way.
"""

from __future__ import annotations

from collections.abc import Callable, Container, Iterable, Sequence

from btplan.model import WILDCARD, Atom, GroundAction, GroundLiteral, matches

INFINITE = float("inf")


def bits(state: int) -> list[int]:
    """The atom numbers set in `state`, lowest first."""
    out = []
    while state:
        low = state & -state
        out.append(low.bit_length() - 1)
        state ^= low
    return out


class PackedActions:
    """Actions as bit masks, indexed by precondition for applicability and h_FF.

    Negative preconditions count for applicability only (h_FF ignores them, as it
    ignores deletes). A negative precondition with a wildcard (`not blocks(_, t)`)
    becomes the mask of every known atom it matches.
    """

    def __init__(self, actions: Sequence[GroundAction]) -> None:
        self.actions = list(actions)
        changed = {a for action in self.actions for a in (*action.add, *action.delete)}
        self.ids: dict[Atom, int] = {}
        self.static: list[tuple[Atom, ...]] = []
        """Each action's positive preconditions that no action changes: true in every
        state reached from a start that has them, so they get no bit (`static_misses`)."""
        for action in self.actions:
            self.static.append(tuple(p.atom for p in action.preconditions
                                     if p.positive and p.atom not in changed))
            for atom in (*(p.atom for p in action.preconditions), *action.add, *action.delete):
                if WILDCARD not in atom.args and (atom in changed or not _positive(action, atom)):
                    self.ids.setdefault(atom, len(self.ids))
        ids = self.ids
        self.atoms = list(ids)
        self.pre: list[tuple[int, ...]] = []
        self.pre_mask: list[int] = []
        self.neg_mask: list[int] = []
        self.add: list[tuple[int, ...]] = []
        self.add_mask: list[int] = []
        self.del_mask: list[int] = []
        self.by_pre: list[list[int]] = [[] for _ in ids]
        self.free: list[int] = []
        for i, action in enumerate(self.actions):
            pre = tuple(dict.fromkeys(ids[p.atom] for p in action.preconditions
                                      if p.positive and p.atom in ids))
            self.pre.append(pre)
            self.pre_mask.append(_mask(pre))
            self.neg_mask.append(self.literal_mask(
                p.atom for p in action.preconditions if not p.positive))
            add = tuple(dict.fromkeys(ids[a] for a in action.add))
            self.add.append(add)
            self.add_mask.append(_mask(add))
            self.del_mask.append(_mask(ids[a] for a in action.delete))
            for number in pre:
                self.by_pre[number].append(i)
            if not pre:
                self.free.append(i)
        self.sizes = [len(pre) for pre in self.pre]
        self._unreached = [-2] * len(ids)
        self._last = 0
        self._waiting = self.sizes[:]
        self._ready: set[int] = set()
        # An action whose preconditions all hold fires when its last one (by number) is
        # taken, after the actions listed before it under that atom.
        count = len(self.actions)
        self._firing = [0] * count
        for number, needers in enumerate(self.by_pre):
            for place, i in enumerate(needers):
                if number == max(self.pre[i]):
                    self._firing[i] = number * count + place
        # `applicable` lists actions by their first precondition, then by number.
        self._anchored = [pre[0] * count + i if pre else i for i, pre in enumerate(self.pre)]
        self._goals: list[int] = []
        self._goal_set: frozenset[int] = frozenset()

    def static_misses(self, start: frozenset[Atom]) -> set[int]:
        """The actions with a precondition that nothing changes and `start` lacks."""
        return {i for i, atoms in enumerate(self.static) if any(a not in start for a in atoms)}

    def literal_mask(self, atoms: Iterable[Atom]) -> int:
        """The bits of `atoms`, a wildcard pattern standing for every known atom it matches."""
        mask = 0
        for atom in atoms:
            if WILDCARD in atom.args:
                mask |= _mask(i for i, known in enumerate(self.atoms) if matches(atom, known))
            elif atom in self.ids:
                mask |= 1 << self.ids[atom]
        return mask

    def encode(self, state: Iterable[Atom]) -> int:
        """A set of atoms as an int; atoms no action reads or writes are left out."""
        ids = self.ids
        return _mask(ids[a] for a in state if a in ids)

    def applicable(self, state: int, true: Sequence[int]) -> list[int]:
        """The actions that can run in `state`, whose set bits are `true` (lowest
        first): those whose positive preconditions all hold (`_taken`, kept from the
        last state asked, which `h_ff` has usually just asked for) and no negative one."""
        neg_mask = self.neg_mask
        found = [i for i in self.free if not state & neg_mask[i]]
        found.extend(i for i in sorted(self._taken(true)[1], key=self._anchored.__getitem__)
                     if not state & neg_mask[i])
        return found

    def apply(self, i: int, state: int) -> int:
        """Delete first, then add (PDDL's order)."""
        return (state & ~self.del_mask[i]) | self.add_mask[i]

    def h_ff(self, true: Sequence[int], goals: Sequence[int]) -> tuple[float, set[int]]:
        """The size of a relaxed plan from the state whose set bits are `true` to
        `goals`, and its actions; infinite when some goal cannot be reached.

        A breadth-first relaxed exploration keeps the first achiever of each atom;
        the relaxed plan is extracted backwards from the goals (Hoffmann and Nebel 2001).
        An action fires as soon as its last precondition is taken from the queue, and
        the exploration stops at the first atom that leaves no goal unreached: the
        supporters already chosen are all the extraction follows.
        """
        supporter = self._unreached[:]  # -2: not reached, -1: true in the state
        for atom in true:
            supporter[atom] = -1
        wanted = self._wanted(goals)
        missing = len([g for g in wanted if supporter[g] == -2])
        if not missing:
            return 0.0, set()
        adds, by_pre = self.add, self.by_pre
        base, holding = self._taken(true)
        waiting = base[:]
        ready = sorted(holding, key=self._firing.__getitem__)
        frontier = list(true)
        for i in (*self.free, *ready):  # in the order taking the state's atoms fires them
            for atom in adds[i]:
                if supporter[atom] == -2:
                    supporter[atom] = i
                    frontier.append(atom)
                    if atom in wanted:
                        missing -= 1
            if not missing:
                break
        head = len(true)
        while missing and head < len(frontier):
            for i in by_pre[frontier[head]]:
                left = waiting[i] - 1
                waiting[i] = left
                if left:
                    continue
                for atom in adds[i]:
                    if supporter[atom] == -2:
                        supporter[atom] = i
                        frontier.append(atom)
                        if atom in wanted:
                            missing -= 1
                if not missing:
                    break
            head += 1
        if missing:
            return INFINITE, set()
        chosen: set[int] = set()
        pre = self.pre
        todo = [g for g in goals if supporter[g] >= 0]
        while todo:
            i = supporter[todo.pop()]
            if i >= 0 and i not in chosen:
                chosen.add(i)
                todo.extend(pre[i])
        return float(len(chosen)), chosen

    def _taken(self, true: Sequence[int]) -> tuple[list[int], set[int]]:
        """The preconditions each action still waits for once the atoms `true` are taken,
        and the actions that leaves waiting for none (neither to be changed).

        Kept for the last state asked and updated by the atoms that differ: a search
        asks for states near each other, and taking a state's own atoms was a third of
        the exploration (the caller copies the list before changing it).
        """
        state = _mask(true)
        by_pre, waiting, ready = self.by_pre, self._waiting, self._ready
        last = self._last
        for atom in bits(last & ~state):
            for i in by_pre[atom]:
                if not waiting[i]:
                    ready.discard(i)
                waiting[i] += 1
        for atom in bits(state & ~last):
            for i in by_pre[atom]:
                left = waiting[i] - 1
                waiting[i] = left
                if not left:
                    ready.add(i)
        self._last = state
        return waiting, ready

    def _wanted(self, goals: Sequence[int]) -> frozenset[int]:
        """`goals` as a set, the last one kept (a search asks for the same goals)."""
        if self._goals != goals:
            self._goals, self._goal_set = list(goals), frozenset(goals)
        return self._goal_set

    def landmarks(self, true: Sequence[int], goals: Sequence[int]) -> int:
        """The atoms every relaxed plan from the state to `goals` makes true at some
        point (fact landmarks by label propagation, Zhu and Givan 2003), as a mask.

        The label of an atom is what must hold before it: an action's label is the
        union of its preconditions' labels, and an atom keeps the intersection of its
        achievers' labels, itself included, until nothing changes.
        """
        label: list[int | None] = [None] * len(self.atoms)
        for atom in true:
            label[atom] = 1 << atom
        pre, adds = self.pre, self.add
        changed = True
        while changed:
            changed = False
            for i in range(len(pre)):
                below = 0
                for atom in pre[i]:
                    known = label[atom]
                    if known is None:
                        break
                    below |= known
                else:
                    for atom in adds[i]:
                        old = label[atom]
                        new = below | 1 << atom if old is None else old & (below | 1 << atom)
                        if new != old:
                            label[atom] = new
                            changed = True
        found = 0
        for goal in goals:
            found |= label[goal] or 0
        return found

    def necessary(self, marks: int, excluded: Container[int] = ()) -> dict[int, int]:
        """For each atom of `marks`, the other atoms of `marks` that every action adding
        it (but those `excluded`) needs, as a mask; only atoms with some are kept.

        These are necessary orderings between landmarks: such an atom must hold again
        before the landmark it comes before can be reached, even where the path made it
        true once already (LAMA's landmarks "needed again").
        """
        common: dict[int, int] = {}
        pre_mask = self.pre_mask
        for i, adds in enumerate(self.add):
            if i in excluded:
                continue
            need = pre_mask[i] & marks
            for atom in adds:
                if marks >> atom & 1:
                    known = common.get(atom)
                    common[atom] = need if known is None else known & need
        return {atom: mask & ~(1 << atom) for atom, mask in common.items()
                if mask & ~(1 << atom)}

    def reasonable(self, marks: int, goals: Sequence[int], needed: dict[int, int],
                   exclusive: Callable[[int, int], bool], excluded: Container[int] = ()
                   ) -> dict[int, int]:
        """For each goal of `goals` in `marks`, the other landmarks of `marks` that should
        be reached before it, as a mask (reasonable orders, Hoffmann, Porteous and
        Sebastia 2004, as LAMA approximates them for goals): a landmark whose every
        achiever deletes the goal, that can never hold with it, or that needs (`needed`)
        an atom that can never hold with it. Reaching the goal first is no progress: it
        must be undone before the other landmark can be reached.
        """
        deletes: dict[int, int] = {}
        for i, adds in enumerate(self.add):
            if i in excluded:
                continue
            gone = self.del_mask[i] & ~self.add_mask[i]
            for atom in adds:
                if marks >> atom & 1:
                    known = deletes.get(atom)
                    deletes[atom] = gone if known is None else known & gone
        out: dict[int, int] = {}
        others = bits(marks)
        for goal in dict.fromkeys(goals):
            if not marks >> goal & 1:
                continue
            before = 0
            for atom in others:
                if atom == goal:
                    continue
                if (deletes.get(atom, 0) >> goal & 1 or exclusive(atom, goal)
                        or any(exclusive(x, goal) for x in bits(needed.get(atom, 0)))):
                    before |= 1 << atom
            if before:
                out[goal] = before
        return out

    def goal_test(self, goal: Sequence[GroundLiteral], start: frozenset[Atom]
                  ) -> tuple[int, int, list[int]] | None:
        """(positive mask, negative mask, positive atom numbers) of a goal; None when it
        can never hold. An atom no action reads or writes keeps its value from `start`."""
        positive: list[Atom] = []
        for literal in goal:
            known = literal.atom in self.ids or (WILDCARD in literal.atom.args
                                                   and not literal.positive)
            if not known and (literal.atom in start) != literal.positive:
                return None
            if known and literal.positive:
                positive.append(literal.atom)
        numbers = [self.ids[a] for a in dict.fromkeys(positive)]
        return _mask(numbers), self.literal_mask(g.atom for g in goal if not g.positive), numbers


def _positive(action: GroundAction, atom: Atom) -> bool:
    """Whether `atom` is a positive precondition of `action` (and nothing else of it)."""
    return atom not in action.add and atom not in action.delete and any(
        p.positive and p.atom == atom for p in action.preconditions)


def _mask(numbers: Iterable[int]) -> int:
    mask = 0
    for number in numbers:
        mask |= 1 << number
    return mask
