"""Which achievers a failed condition gets: ranked, without circular, banned or dead-end ones.

The planner ranks the candidates (btplan.planner.achievers) and judges reachability
(btplan.planner.lookahead); what depends on the run is here: the choices an earlier
attempt banned, and the conditions the enclosing Fallbacks already pursue; with
`goal_credit`, the goals an achiever's effects make true (btplan.acting.credit).
"""

from __future__ import annotations

from btplan.acting.credit import credit_goals
from btplan.acting.state import LoopState
from btplan.bt import Node
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.achievers import ALL
from btplan.planner.expand import non_circular, pursued
from btplan.planner.lookahead import keep_reachable, needed_later


def achievers_for(loop: LoopState, node: Node, literal: GroundLiteral,
                  state: frozenset[Atom]) -> tuple[list[GroundAction], list[GroundAction]]:
    """Ranked achievers of a failed condition, without circular or dead-end ones,
    and the ranked candidates left over (for backtracking)."""
    options, index = loop.options, loop.index
    width = options.max_alternatives
    if not options.avoid_dead_ends:
        achievers = index.achievers(literal, state, loop.world.refine,
                                    ALL if loop.banned else None)
        kept = allowed(loop, _non_circular(loop, achievers, node, literal), literal)
        return kept[:width], []
    # Rank every candidate, so that dropping dead ends still leaves `width` of them;
    # circular ones are dropped before ranking (the same list, cheaper).
    if options.refine_more:
        achievers, circular = index.achievers_avoiding(literal, state, loop.world.refine,
                                                       pursued(node))
        if circular:
            loop.circular.add(literal)
    else:
        achievers = index.achievers(literal, state, loop.world.refine, ALL)
    achievers = allowed(loop, achievers, literal)
    if loop.goal_credit:  # the goals their effects make true count (credit.py)
        achievers = credit_goals(achievers, literal, loop.task.goal_literals,
                                 index.relaxed, state)
    if len(achievers) < 2:  # what keep_reachable does then, without reading the tree
        kept = list(achievers[:width])
    else:
        kept = keep_reachable(achievers, needed_later(node), index.relaxed, state, width)
    chosen = {a.key for a in kept}  # keys: comparing whole actions is slow
    return kept, [a for a in achievers if a.key not in chosen]


def allowed(loop: LoopState, achievers: list[GroundAction],
            literal: GroundLiteral) -> list[GroundAction]:
    """Achievers not banned for this condition by an earlier attempt."""
    if not loop.banned:
        return achievers
    return [a for a in achievers if (literal, a.key) not in loop.banned]


def _non_circular(loop: LoopState, achievers: list[GroundAction], node: Node,
                  literal: GroundLiteral) -> list[GroundAction]:
    """Drop circular achievers (with refine_more), remembering when that left none."""
    if not loop.options.refine_more or not achievers:
        return achievers
    kept = non_circular(achievers, pursued(node))
    if achievers and not kept:
        loop.circular.add(literal)
    return kept
