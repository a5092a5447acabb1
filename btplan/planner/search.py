"""The last resort: a complete search, for one stuck condition or for the whole goal.

When backchaining finds no conflict-free place for the subtree achieving a condition,
or every achiever of it is circular, the paper stops. btplan then searches, from the
state the tree reached, for a plan that makes the condition true while keeping what
the enclosing sequences already hold, and btplan/planner/rescue.py turns that plan
into a reactive subtree; when backchaining fails as a whole, the same search plans the
whole goal (btplan/acting/offline.py). The search sees every grounding of the relaxed
model, so it is only bounded by its budget of states; it is the exception, and the
summary counts it.

The search is a satisficing planner's greedy best-first search (as in LAMA, Richter
and Westphal 2010): deferred evaluation (a state is evaluated when taken from a queue,
with its parent's estimate until then), two estimates (h_FF and the count of fact
landmarks not yet reached on the path), and for each a second queue holding only the
children of preferred actions (those of the relaxed plan that can run now); the
queues take turns, and every time an estimate improves the preferred queues get
BOOST turns ahead. States are ints (btplan/planner/packed.py).
"""

from __future__ import annotations

import heapq
import itertools
import time
from collections.abc import Sequence

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.packed import INFINITE, PackedActions, bits

MAX_STATES = 2000
"""States expanded (each one h_FF evaluation) by one search before it gives up."""

BOOST = 1000
"""Turns the preferred queues get ahead each time an estimate improves (LAMA's value)."""

Parents = dict[int, tuple[int, int] | None]


class SubgoalSearch:
    """Lazy greedy best-first search with h_FF, landmarks and preferred actions."""

    def __init__(self, actions: Sequence[GroundAction]) -> None:
        self.actions = [a for a in actions if not a.delete_patterns]
        self.packed = PackedActions(self.actions)
        self.expanded = 0
        """States the last search expanded (for the failure message)."""
        self.exhausted = False
        """Whether the last search ran out of states to look at (no plan exists)."""
        self.use_landmarks = True
        """Whether the landmark queues take part (off: h_FF and its preferred queue only)."""
        self.boost = BOOST

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

        `max_stored` bounds the states kept, expanded or waiting (memory, where
        branching is wide). A state reached again keeps its first parent.

        No step may make a `keep` literal false: the plan runs where earlier siblings
        re-check their conditions on every tick, so undoing one would send the tree
        back to them.

        Negative goal literals count for the estimates only as satisfied or not (one
        action each when not).
        """
        packed = self.packed
        self.expanded, self.exhausted = 0, False
        test = packed.goal_test(goal, start)
        if test is None:
            self.exhausted = True
            return None
        positive, negative, numbers = test
        banned = self._banned(keep, start)
        first = packed.encode(start)
        marks = packed.landmarks(bits(first), numbers) & ~first if self.use_landmarks else 0
        queues: list[list[tuple[float, int, int, int, int]]] = [[] for _ in range(4 if marks else 2)]
        turns = [0] * len(queues)
        best = [INFINITE] * 2
        counter = itertools.count()
        queues[0].append((0.0, next(counter), first, -1, -1))
        parents: Parents = {first: None}  # each state's first parent: one entry per queue
        reached: dict[int, int] = {}  # the landmarks each expanded state's path reached
        while True:
            chosen = _turn(queues, turns)
            if chosen is None:
                self.exhausted = True
                return None
            _, _, state, parent, action = heapq.heappop(queues[chosen])
            if state in reached:
                continue
            if state & positive == positive and not state & negative:
                return self._path(parents, state)
            true = bits(state)
            h, relaxed = packed.h_ff(true, numbers)
            if h == INFINITE:
                reached[state] = 0  # a dead end: never looked at again
                continue
            h += bin(state & negative).count("1")
            passed = reached[state] = (0 if parent < 0 else reached[parent]) | (state & marks)
            estimates = (h, (bin(marks & ~passed).count("1")
                             + bin(positive & passed & ~state).count("1")) if marks else h)
            self._improved(estimates, best, turns)
            self.expanded += 1
            if self._over(max_states, deadline, max_stored, parents, queues):
                return None
            for i in packed.applicable(state, true):
                if i in banned:
                    continue
                child = packed.apply(i, state)
                if child in parents:
                    continue
                parents[child] = (state, i)
                number = next(counter)
                for q in range(0, len(queues), 2):
                    estimate = estimates[q // 2]
                    heapq.heappush(queues[q], (estimate, number, child, state, i))
                    if i in relaxed:
                        heapq.heappush(queues[q + 1], (estimate, number, child, state, i))

    def _banned(self, keep: Sequence[GroundLiteral], start: frozenset[Atom]) -> set[int]:
        """The actions that would make a `keep` literal false."""
        if not keep:
            return set()
        packed = self.packed
        held = packed.literal_mask(k.atom for k in keep if k.positive)
        absent = packed.literal_mask(k.atom for k in keep if not k.positive)
        return {i for i in range(len(self.actions))
                if packed.del_mask[i] & held & ~packed.add_mask[i]
                or packed.add_mask[i] & absent}

    def _improved(self, estimates: tuple[float, float], best: list[float],
                  turns: list[int]) -> None:
        """Note better estimates; each improvement moves the preferred queues ahead."""
        for k, value in enumerate(estimates[:len(turns) // 2]):
            if value < best[k]:
                best[k] = value
                for q in range(1, len(turns), 2):
                    turns[q] -= self.boost

    def _over(self, max_states: int, deadline: float | None, max_stored: int | None,
              parents: Parents, queues: list[list[tuple[float, int, int, int, int]]]) -> bool:
        """Whether a budget ran out: states expanded, time, or states stored."""
        if self.expanded >= max_states:
            return True
        if self.expanded % 32 == 0:
            if deadline is not None and time.perf_counter() > deadline:
                return True
            if max_stored is not None and len(parents) > max_stored:
                return True
        return False

    def _path(self, parents: Parents, state: int) -> list[GroundAction]:
        steps: list[GroundAction] = []
        link = parents[state]
        while link is not None:
            state, i = link
            steps.append(self.actions[i])
            link = parents[state]
        steps.reverse()
        return steps


def _turn(queues: list[list[tuple[float, int, int, int, int]]], turns: list[int]) -> int | None:
    """The non-empty queue whose turn it is (fewest turns taken, boosts counted)."""
    chosen = None
    for q, queue in enumerate(queues):
        if queue and (chosen is None or turns[q] < turns[chosen]):
            chosen = q
    if chosen is not None:
        turns[chosen] += 1
    return chosen
