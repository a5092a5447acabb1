"""Looking ahead along an action's preconditions before the robot starts acting.

A Sequence ticks its children left to right and stops at the first that fails, so
Algorithm 1 only ever sees the first false precondition of an action. When a later
one is false too, the robot first achieves the earlier one, and finds the later one
false only then: in blocksworld it picks up the block to stack, then finds the target
covered, and (since unstacking needs an empty hand) puts the block down again. Seeing
the later conditions false in the same state, before anything runs, lets conflict
resolution order the subtrees as a plan would, and costs no tick of the world.
"""

from __future__ import annotations

from collections.abc import Collection

from btplan.bt import Node, Sequence
from btplan.model import Atom
from btplan.planner import literal_of


def attached(node: Node, root: Node) -> bool:
    """Whether `node` is still in the tree under `root` (a move may have cut it off)."""
    while node.parent is not None:
        node = node.parent
    return node is root


def later_false(node: Node, state: frozenset[Atom], expanded: Collection[Node]) -> list[Node]:
    """The condition siblings after `node` in its Sequence that do not hold in `state`.

    Only plain, not yet expanded conditions: an expanded one already has its subtree.
    """
    parent = node.parent
    if not isinstance(parent, Sequence):
        return []
    siblings = parent.children
    out = []
    for sibling in siblings[siblings.index(node) + 1:]:
        literal = literal_of(sibling)
        if literal is not None and sibling not in expanded and not literal.holds(state):
            out.append(sibling)
    return out
