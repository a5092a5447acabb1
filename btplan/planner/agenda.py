"""A goal agenda: reasonable orders between the goals, before the tree is built.

The paper's tree starts as `Sequence(goals)` in the order the problem lists them, and
conflict resolution moves subtrees when that order is wrong, at the price of a
restart from the initial state per move. Goal g1 is reasonably ordered before g2
(Koehler and Hoffmann 2000) when g1 cannot be achieved while g2 holds: every action
adding g1 needs a condition h^2-exclusive with g2, or deletes g2. In blocksworld,
stack(b, c) needs holding(b), which excludes on(a, b): on(b, c) comes first.

Those orders look at the actions only. With the initial state, g1 is also ordered
before g2 when g1 is unreachable, ignoring deletes, from the initial state once no
atom exclusive with g2 may be made true (`state_orders`): building on(b8, b7) while b7
still sits on b37 blocks on(b37, b23), since b37 cannot be cleared while b7 stays
covered.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable, Sequence

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.classical import RelaxedModel
from btplan.classical import Mutexes

Orders = dict[GroundLiteral, set[GroundLiteral]]
_KEPT: weakref.WeakKeyDictionary[RelaxedModel, dict[tuple[GroundLiteral, ...], Orders]] = (
    weakref.WeakKeyDictionary())


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


def state_orders(
    goals: Sequence[GroundLiteral], mutexes: Mutexes, relaxed: RelaxedModel,
    state: frozenset[Atom],
) -> Orders:
    """For each goal g2, the goals that cannot be reached from `state` while g2 is kept.

    Kept means that no atom exclusive with g2 is made true (atoms of `state` stay as
    they are: g2 need not hold yet). Only atoms sharing an object with g2, or with
    none, are asked about (exclusion is about the same objects: the hand, a block's
    place). One relaxed reachability run per goal, remembered per relaxed model, since
    every planning attempt of a task asks again.
    """
    kept = _KEPT.setdefault(relaxed, {})
    key = tuple(goals)
    if key in kept:
        return kept[key]
    by_object: dict[str, set[Atom]] = {}
    bare: set[Atom] = set()
    for action in relaxed.actions:
        for atom in action.add:
            if atom in state:
                continue
            if not atom.args:
                bare.add(atom)
            for arg in atom.args:
                by_object.setdefault(arg, set()).add(atom)
    orders: Orders = {}
    positive = [g for g in goals if g.positive]
    for goal in positive:
        near = set(bare).union(*(by_object.get(a, set()) for a in goal.atom.args))
        avoided = {a for a in near if mutexes.knows(a)
                   and mutexes.exclusive(GroundLiteral(a, True), goal)}
        others = [h.atom for h in positive if h != goal]
        if not avoided or not others:
            continue
        reached = relaxed.reachable_avoiding(state, avoided, others)
        orders[goal] = {h for h in positive if h != goal and h.atom not in reached}
    kept[key] = orders
    return orders


def goal_agenda(
    goals: Sequence[GroundLiteral],
    producers: Callable[[Atom], list[GroundAction]], mutexes: Mutexes,
    extra: Orders | None = None,
) -> list[GroundLiteral]:
    """The goals in an order that respects the reasonable orders between them (and
    the `extra` ones, goal -> goals to come before it, from `state_orders`).

    A stable topological order: among the goals whose predecessors are placed, the one
    listed first goes next; a cycle is broken at the goal listed first.
    """
    before = {g: {h for h in goals if reasonable_before(h, g, producers, mutexes)}
              | (extra or {}).get(g, set()) for g in goals}
    placed: list[GroundLiteral] = []
    left = list(dict.fromkeys(goals))
    while left:
        ready = [g for g in left if not (before[g] - set(placed))]
        pick = ready[0] if ready else left[0]
        placed.append(pick)
        left.remove(pick)
    return placed
