"""Keeping a later goal reachable: the "white knight" of classic plan-space planning.

An achiever can destroy the last source of what another goal needs: to swap two
registers, copying r2 into r1 loses the only copy of r1's value, which r2 needs next.
No order of the subtrees helps, so backchaining stops there. This step looks, for each
goal that the achiever would make unreachable (ignoring deletes from then on), for one
condition that, made true first and untouched by the achiever, keeps the goal
reachable (holds(r3, a): save the value in the spare register), and returns it so it
can be checked before the achiever runs; its own expansion then achieves it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.classical import RelaxedModel


def white_knights(
    action: GroundAction,
    state: frozenset[Atom],
    goals: Iterable[GroundLiteral],
    relaxed: RelaxedModel,
) -> list[Atom]:
    """Conditions to make true before `action` so that no goal becomes unreachable."""
    after = action.apply(state)
    found: list[Atom] = []
    for goal in goals:
        if not goal.positive or goal.atom in state:
            continue
        if relaxed.estimate(state, [goal.atom]) == math.inf:
            continue
        if relaxed.estimate(after, [goal.atom]) < math.inf:
            continue
        knight = _best_knight(action, state, after, goal.atom, relaxed)
        if knight is not None and knight not in found:
            found.append(knight)
    return found


def _best_knight(
    action: GroundAction,
    state: frozenset[Atom],
    after: frozenset[Atom],
    goal: Atom,
    relaxed: RelaxedModel,
) -> Atom | None:
    candidates: list[tuple[float, str, Atom]] = []
    for producer in relaxed.producers(goal):
        for pre in producer.preconditions:
            atom = pre.atom
            if not pre.positive or atom in after or action.deletes(atom):
                continue
            cost = relaxed.estimate(state, [atom])
            if cost == math.inf:
                continue
            if relaxed.estimate(after | {atom}, [goal]) < math.inf:
                candidates.append((cost, str(atom), atom))
    return min(candidates)[2] if candidates else None
