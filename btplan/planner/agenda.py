"""A goal agenda: reasonable orders between the goals, before the tree is built.

The paper's tree starts as `Sequence(goals)` in the order the problem lists them, and
conflict resolution moves subtrees when that order is wrong, at the price of a
restart from the initial state per move. Goal g1 is reasonably ordered before g2
(Koehler and Hoffmann 2000) when g1 cannot be achieved while g2 holds: every action
adding g1 needs a condition h^2-exclusive with g2, or deletes g2. In blocksworld,
stack(b, c) needs holding(b), which excludes on(a, b): on(b, c) comes first.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.mutex import Mutexes


def reasonable_before(
    first: GroundLiteral, second: GroundLiteral,
    producers: Callable[[Atom], list[GroundAction]], mutexes: Mutexes,
) -> bool:
    """Whether `first` cannot be achieved while `second` holds (so it should come first)."""
    if not (first.positive and second.positive) or first == second:
        return False
    makers = producers(first.atom)
    if not makers:
        return False
    for action in makers:
        if action.deletes(second.atom):
            continue
        if not any(p.positive and mutexes.exclusive(p, second) for p in action.preconditions):
            return False
    return True


def goal_agenda(
    goals: Sequence[GroundLiteral],
    producers: Callable[[Atom], list[GroundAction]], mutexes: Mutexes,
) -> list[GroundLiteral]:
    """The goals in an order that respects the reasonable orders between them.

    A stable topological order: among the goals whose predecessors are placed, the one
    listed first goes next; a cycle is broken at the goal listed first.
    """
    before = {g: {h for h in goals if reasonable_before(h, g, producers, mutexes)}
              for g in goals}
    placed: list[GroundLiteral] = []
    left = list(dict.fromkeys(goals))
    while left:
        ready = [g for g in left if not (before[g] - set(placed))]
        pick = ready[0] if ready else left[0]
        placed.append(pick)
        left.remove(pick)
    return placed
