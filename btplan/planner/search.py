"""The last resort for one stuck condition: a complete search, its plan made a subtree.

When backchaining finds no conflict-free place for the subtree achieving a condition,
or every achiever of it is circular, the paper stops. btplan then searches, from the
state the tree reached, for a plan that makes the condition true while keeping what
the enclosing sequences already hold (greedy best-first search with h_FF, helpful
actions first; Hoffmann and Nebel 2001), and btplan/planner/rescue.py turns that plan
into a reactive subtree. The search sees every grounding of the relaxed model, so it is only
bounded by its budget of states; it is the exception, and the summary counts it.
"""

from __future__ import annotations

import heapq
import itertools
import time
from collections import deque
from collections.abc import Sequence

from btplan.model import Atom, GroundAction, GroundLiteral

MAX_STATES = 2000
"""States expanded (each one h_FF evaluation) by one search before it gives up."""


class SubgoalSearch:
    """Greedy best-first search with h_FF over a fixed list of grounded actions."""

    def __init__(self, actions: Sequence[GroundAction]) -> None:
        self.actions = [a for a in actions if not a.delete_patterns]
        self.expanded = 0
        """States the last search expanded (for the failure message)."""
        self.exhausted = False
        """Whether the last search ran out of states to look at (no plan exists)."""
        self._ids: dict[Atom, int] = {}
        self._pre: list[tuple[int, ...]] = []
        self._add: list[tuple[int, ...]] = []
        self._by_pre: dict[int, list[int]] = {}
        self._anchor: dict[Atom, list[int]] = {}
        self._free: list[int] = []
        self._sizes: list[int] = []
        for i, action in enumerate(self.actions):
            positive = tuple(dict.fromkeys(p.atom for p in action.preconditions if p.positive))
            pre = tuple(self._id(a) for a in positive)
            self._pre.append(pre)
            self._sizes.append(len(pre))
            self._add.append(tuple(self._id(a) for a in action.add))
            for atom in pre:
                self._by_pre.setdefault(atom, []).append(i)
            if positive:
                self._anchor.setdefault(positive[0], []).append(i)
            else:
                self._free.append(i)

    def _id(self, atom: Atom) -> int:
        found = self._ids.get(atom)
        if found is None:
            found = self._ids[atom] = len(self._ids)
        return found

    def applicable(self, state: frozenset[Atom]) -> list[int]:
        """Indices of the actions that can run in `state` (found through one precondition)."""
        found = [i for i in self._free if self.actions[i].applicable(state)]
        for atom in state:
            for i in self._anchor.get(atom, ()):
                if self.actions[i].applicable(state):
                    found.append(i)
        return found

    def h_ff(self, state: frozenset[Atom], goal: Sequence[Atom]) -> tuple[float, set[int]]:
        """The size of a relaxed plan from `state` to `goal`, and its actions.

        A layered relaxed exploration (first achiever of each atom kept), then the
        relaxed plan extracted backwards from the goal; infinite when unreachable.
        """
        ids = self._ids
        reached: dict[int, int | None] = {ids[a]: None for a in state if a in ids}
        targets = []
        for atom in goal:
            if atom not in state:
                if atom not in ids:
                    return float("inf"), set()
                targets.append(ids[atom])
        missing = set(targets)
        waiting = list(self._sizes)
        frontier = deque(reached)
        for i in self._free:
            self._fire(i, reached, frontier, missing)
        while frontier and missing:
            for i in self._by_pre.get(frontier.popleft(), ()):
                waiting[i] -= 1
                if waiting[i] == 0:
                    self._fire(i, reached, frontier, missing)
        if missing:
            return float("inf"), set()
        chosen: set[int] = set()
        todo = list(targets)
        done: set[int] = set()
        while todo:
            needed = todo.pop()
            if needed in done:
                continue
            done.add(needed)
            supporter = reached[needed]
            if supporter is None or supporter in chosen:
                continue
            chosen.add(supporter)
            todo.extend(self._pre[supporter])
        return float(len(chosen)), chosen

    def _fire(self, i: int, reached: dict[int, int | None], frontier: deque[int],
              missing: set[int]) -> None:
        for atom in self._add[i]:
            if atom not in reached:
                reached[atom] = i
                frontier.append(atom)
                missing.discard(atom)

    def search(
        self,
        start: frozenset[Atom],
        goal: Sequence[GroundLiteral],
        max_states: int = MAX_STATES,
        deadline: float | None = None,
        keep: Sequence[GroundLiteral] = (),
        max_stored: int | None = None,
    ) -> list[GroundAction] | None:
        """A plan from `start` to a state where every goal literal holds, or None.

        `max_stored` bounds the states kept (each a set of atoms: memory, where
        branching is wide).

        No step may make a `keep` literal false: the plan runs where earlier siblings
        re-check their conditions on every tick, so undoing one would send the tree
        back to them.

        Negative goal literals count for the heuristic only as satisfied or not (one
        action each when not). Children of helpful actions (those of the relaxed plan
        that can run now) are looked at first among equal estimates.
        """
        positive = [g.atom for g in goal if g.positive]
        negative = [g for g in goal if not g.positive]

        def estimate(state: frozenset[Atom]) -> tuple[float, set[int]]:
            h, relaxed = self.h_ff(state, positive)
            return h + sum(1 for g in negative if not g.holds(state)), relaxed

        parents: dict[frozenset[Atom], tuple[frozenset[Atom], int] | None] = {start: None}
        counter = itertools.count()
        # Deferred evaluation: a child waits with its parent's estimate and is evaluated
        # only when taken; children of helpful actions are taken first on ties.
        queue: list[tuple[float, int, int, frozenset[Atom]]] = [(0.0, 0, next(counter), start)]
        expanded = self.expanded = 0
        self.exhausted = False
        while queue and expanded < max_states:
            _, _, _, state = heapq.heappop(queue)
            if all(g.holds(state) for g in goal):
                return self._path(parents, state)
            h, helpful = estimate(state)
            if h == float("inf"):
                continue
            expanded = self.expanded = expanded + 1
            if deadline is not None and expanded % 32 == 0 and time.perf_counter() > deadline:
                return None
            if max_stored is not None and len(parents) > max_stored:
                return None
            for i in self.applicable(state):
                if keep and any(_falsifies(self.actions[i], k) for k in keep):
                    continue
                child = self.actions[i].apply(state)
                if child in parents:
                    continue
                parents[child] = (state, i)
                heapq.heappush(queue, (h, 0 if i in helpful else 1, next(counter), child))
        self.exhausted = not queue
        return None

    def _path(
        self, parents: dict[frozenset[Atom], tuple[frozenset[Atom], int] | None],
        state: frozenset[Atom],
    ) -> list[GroundAction]:
        steps: list[GroundAction] = []
        link = parents[state]
        while link is not None:
            state, i = link
            steps.append(self.actions[i])
            link = parents[state]
        steps.reverse()
        return steps


def _falsifies(action: GroundAction, literal: GroundLiteral) -> bool:
    if literal.positive:
        return action.deletes(literal.atom)
    return literal.atom in action.add
