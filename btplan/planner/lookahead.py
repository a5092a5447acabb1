"""Looking ahead with the relaxed model: which condition to expand, which achievers to keep.

Two departures from the paper (docs/design/, records 13 and 12), both measured on
competition domains:

* The paper expands the first failed condition in breadth-first order (Algorithm 3).
  A Fallback whose first alternative fails ticks the next one, so every alternative's
  first failed condition is a candidate, and breadth first expands them all level by
  level: reaching a place d moves away costs about 4^d expansions on a grid (visitall
  ran out of its 1000 expansions this way). `closest_first` expands the failed
  condition with the smallest h_add from the current state instead, breadth-first
  order breaking ties: the alternative nearest to the state is deepened first.
* An achiever can make a condition that the enclosing sequences still need unreachable
  for good: making a plain sandwich for a child who needs a gluten-free one uses up
  the sandwich (child-snack), and the tree then tries the next alternative with what
  is left, until nothing is. `keep_reachable` drops such achievers while others remain.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from btplan.bt import Fallback, Node
from btplan.bt import Sequence as SequenceNode
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.conflicts import guarantees
from btplan.planner.expand import literal_of
from btplan.classical import RelaxedModel


def closest_first(
    failed: Sequence[Node], relaxed: RelaxedModel, state: frozenset[Atom]
) -> list[Node]:
    """Failed conditions by h_add from `state`, breadth-first order breaking ties."""
    costs = relaxed.costs(state)

    def distance(node: Node) -> float:
        literal = literal_of(node)
        if literal is None or not literal.positive:
            return 1.0  # a deletion is one action away, as far as the relaxation sees
        return costs.get(literal.atom, math.inf)

    order = {id(node): i for i, node in enumerate(failed)}
    return sorted(failed, key=lambda n: (distance(n), order[id(n)]))


def needed_later(condition: Node) -> list[GroundLiteral]:
    """Positive conditions the enclosing sequences need once `condition` holds.

    Those are the later siblings along the chain of Sequence ancestors and the
    conditions the enclosing Fallbacks pursue (what the whole branch is for).
    """
    needed: list[GroundLiteral] = []
    child: Node = condition
    parent = condition.parent
    while parent is not None:
        if isinstance(parent, SequenceNode):
            for later in parent.children[parent.index_of(child) + 1:]:
                needed += guarantees(later)
        elif isinstance(parent, Fallback) and parent.children and child is not parent.children[0]:
            first = literal_of(parent.children[0])
            if first is not None:
                needed.append(first)
        child, parent = parent, parent.parent
    own = literal_of(condition)
    return [g for g in dict.fromkeys(needed) if g.positive and g != own]


TEMPLATE_FAILURES = 3
"""Groundings of one template found to cut something off before the rest are skipped."""


def keep_reachable(
    achievers: Sequence[GroundAction],
    needed: Sequence[GroundLiteral],
    relaxed: RelaxedModel,
    state: frozenset[Atom],
    width: int,
    checks: int = 64,
) -> list[GroundAction]:
    """The first `width` achievers after whose effects all `needed` stays reachable.

    Conditions unreachable already are not held against anyone. At most `checks`
    achievers are tried (each costs a relaxed reachability run), and a template is
    passed over once TEMPLATE_FAILURES of its groundings failed. The verdict is trusted
    only when some achiever that passes can run now: for one that cannot, the effects
    of reaching its preconditions are unknown (copying into a register first takes a
    copy into it), so then the first `width` are kept, unfiltered.
    """
    if not needed or len(achievers) < 2:
        return list(achievers[:width])
    now = relaxed.costs(state)
    targets = [g.atom for g in needed if g.atom in now]
    if not targets:
        return list(achievers[:width])
    safe: list[GroundAction] = []
    failures: dict[str, int] = {}
    for action in achievers:
        if failures.get(action.name, 0) >= TEMPLATE_FAILURES:
            continue  # its groundings tend to share the verdict; look at other templates
        if checks == 0:
            break
        checks -= 1
        after = action.apply(state)
        # What is reachable from `after` includes all that was, once what the action
        # deleted is reachable again: then the targets need no look (a cheap, early exit).
        lost = state - after
        if (_back_in_one_step(lost, after, relaxed) or relaxed.reachable(after, lost)
                or relaxed.reachable(after, targets)):
            safe.append(action)
            if len(safe) == width:
                break
        else:
            failures[action.name] = failures.get(action.name, 0) + 1
    if not any(a.applicable(state) for a in safe):
        return list(achievers[:width])
    return safe


def _back_in_one_step(lost: frozenset[Atom], after: frozenset[Atom], relaxed: RelaxedModel
                      ) -> bool:
    """Whether, for each atom in `lost`, some grounding whose positive preconditions all
    hold in `after` adds it back: then `relaxed.reachable(after, lost)` holds, known
    without a search (an achiever is usually undone by its inverse: unstack what was
    stacked). keep_reachable asks this for every achiever it checks."""
    holds = after.__contains__
    for atom in lost:
        for needs in relaxed.producer_needs(atom):
            if all(map(holds, needs)):
                break
        else:
            return False
    return True
