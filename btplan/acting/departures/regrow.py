"""Re-expansion: new achievers for a condition that was expanded and fails again.

Refinement depends on the state (the paper's RefineActions), so the achievers chosen
when a condition was first expanded may not fit the state it fails in later. Appending
alternatives to its Fallback keeps the tree growing, never rebuilt.
"""

from __future__ import annotations

from btplan.acting.choice import allowed
from btplan.acting.diagnosis import most_expanded
from btplan.acting.hooks import Departure
from btplan.acting.state import Expansion, LoopState
from btplan.bt import FAILURE, Fallback, Node
from btplan.errors import BudgetExceededError, UnresolvableConflictError
from btplan.model import Atom, GroundAction
from btplan.planner import literal_of, resolve_conflicts
from btplan.planner.achievers import guards
from btplan.planner.conflicts import achiever_leaves, alternative_conflicts
from btplan.planner.expand import (
    achiever_sequence,
    conditions_bfs,
    non_circular,
    not_through_pursued,
    pursued,
)


def reexpand(loop: LoopState, state: frozenset[Atom]) -> Expansion | None:
    """Give the first failed, already expanded condition (breadth first) the achievers
    that apply in `state` and are not in its Fallback yet."""
    options = loop.options
    for node in conditions_bfs(loop.tree.root):
        fallback = node.parent
        if (node.status is not FAILURE or node not in loop.expanded or node in loop.dead
                or not isinstance(fallback, Fallback) or fallback.children[0] is not node
                or fallback.status is not FAILURE):
            continue
        literal = literal_of(node)
        assert literal is not None
        present = {leaf.key for leaf in achiever_leaves(fallback)}
        limit = len(present) + options.max_alternatives
        found = loop.index.achievers(literal, state, loop.world.refine, limit)
        goals = pursued(node)
        fresh = [a for a in allowed(loop, non_circular(found, goals), literal)
                 if a.key not in present]
        fresh = not_through_pursued(fresh, goals, loop.index.relaxed, state,
                                    loop.task.object_types)
        if fresh and len(loop.expansions) >= options.max_expansions:
            raise BudgetExceededError(
                f"the expansion budget ({options.max_expansions}) ran out while {literal} "
                f"still fails; expanded most often: {most_expanded(loop.expansions)}"
            )
        grown = _append_alternatives(loop, fallback, fresh)
        if grown is not None:
            added, conflicts, moves = grown
            return loop.record(literal, added, conflicts, moves)
    return None


def _append_alternatives(
    loop: LoopState, fallback: Fallback, actions: list[GroundAction]
) -> tuple[list[GroundAction], int, int] | None:
    """Append achievers to an expanded condition's fallback, as ExpandTree would.

    New alternatives that conflict are dropped if others do not; if all do, the
    fallback is moved like a new subtree (the goal order may have to change now);
    if no place is free of conflicts, nothing is added.
    """
    judge = loop.judge()
    appended: list[tuple[GroundAction, Node]] = []
    literal = literal_of(fallback.children[0])
    assert literal is not None
    state = loop.world.facts()
    for action in actions[: loop.options.max_alternatives]:
        loop.ground([action])
        guard = guards(action, literal, state)
        alternative = achiever_sequence(action, loop.task, guard)
        loop.never_expand(alternative.children[: len(guard)])
        fallback.append(alternative)
        appended.append((action, alternative))
    clean = [(a, n) for a, n in appended if not alternative_conflicts(fallback, n, judge)]
    if clean:
        for action, node in appended:
            if (action, node) not in clean:
                fallback.remove(node)
        return [a for a, _ in clean], 0, 0
    if not appended or not loop.options.reorder_goals:
        for _, node in appended:
            fallback.remove(node)
        return None
    try:
        resolution = resolve_conflicts(loop.tree, fallback, judge, True, False)
    except UnresolvableConflictError:
        for _, node in appended:
            fallback.remove(node)
        return None
    return [a for a, _ in appended], len(resolution.conflicts), resolution.moves


class Regrow(Departure):
    """The `refine_more` option of the planner, when nothing new is left to expand."""

    name = "refine_more"

    def expand_again(self, state: frozenset[Atom]) -> Expansion | None:
        """The `expand_again` hook: when nothing new is left to expand, give a failed expanded
        condition achievers that fit the state now (`reexpand`); None when none has any."""
        return reexpand(self.loop, state)
