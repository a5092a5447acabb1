"""Which achievers a failed condition gets: ranked, without circular, banned or dead-end ones.

The planner ranks the candidates (btplan.planner.achievers) and judges reachability
(btplan.planner.lookahead); what depends on the run is here: the choices an earlier
attempt banned, the conditions the enclosing Fallbacks already pursue, and the
departures' own ranking (`Hooks.rank_achievers`: credit for other goals).
"""

from __future__ import annotations

from collections.abc import Callable

from btplan.acting.state import LoopState
from btplan.bt import Node
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.achievers import ALL
from btplan.planner.expand import non_circular, pursued
from btplan.planner.lookahead import keep_reachable, needed_later

Rank = Callable[[list[GroundAction], GroundLiteral, frozenset[Atom]], list[GroundAction]]
"""The departures' ranking of achievers (btplan.acting.hooks)."""


def achievers_for(loop: LoopState, node: Node, literal: GroundLiteral,
                  state: frozenset[Atom], rank: Rank
                  ) -> tuple[list[GroundAction], list[GroundAction], bool]:
    """Ranked achievers of a failed condition, without circular or dead-end ones, the
    ranked candidates left over (for backtracking), and whether dropping circular ones
    left none (for the message when the loop is stuck)."""
    options, index = loop.options, loop.index
    width = options.max_alternatives
    if not options.avoid_dead_ends:
        achievers = index.achievers(literal, state, loop.world.refine,
                                    ALL if loop.banned else None)
        kept, circular = _non_circular(loop, achievers, node)
        return allowed(loop, kept, literal)[:width], [], circular
    # Rank every candidate, so that dropping dead ends still leaves `width` of them;
    # circular ones are dropped before ranking (the same list, cheaper).
    circular = False
    if options.refine_more:
        achievers, circular = index.achievers_avoiding(literal, state, loop.world.refine,
                                                       pursued(node))
    else:
        achievers = index.achievers(literal, state, loop.world.refine, ALL)
    achievers = rank(allowed(loop, achievers, literal), literal, state)
    if len(achievers) < 2:  # what keep_reachable does then, without reading the tree
        kept = list(achievers[:width])
    else:
        kept = keep_reachable(achievers, needed_later(node), index.relaxed, state, width)
    chosen = {a.key for a in kept}  # keys: comparing whole actions is slow
    return kept, [a for a in achievers if a.key not in chosen], circular


def allowed(loop: LoopState, achievers: list[GroundAction],
            literal: GroundLiteral) -> list[GroundAction]:
    """Achievers not banned for this condition by an earlier attempt."""
    if not loop.banned:
        return achievers
    return [a for a in achievers if (literal, a.key) not in loop.banned]


def _non_circular(loop: LoopState, achievers: list[GroundAction],
                  node: Node) -> tuple[list[GroundAction], bool]:
    """Drop circular achievers (with refine_more); whether that left none."""
    if not loop.options.refine_more or not achievers:
        return achievers, False
    kept = non_circular(achievers, pursued(node))
    return kept, bool(achievers and not kept)
