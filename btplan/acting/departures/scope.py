"""A subtree moved out of an achiever runs only while that achiever is still needed.

Conflict resolution moves a new subtree before the siblings that would undo what it
needs (Algorithm 1, lines 11-12): in Example 2 the subtree that clears the path to the
goal needs an empty hand, so it goes before the subtree that picks the cube, to the
front of the goal's Sequence. There it is ticked first on every tick, also when the
condition it was moved for no longer needs it: the robot stands at the goal with the
cube, the sphere rolls onto the path behind it, and the tree halts Place, drops the
cube and clears a path it will not use again.

The subtree was only there to make an action of the Fallbacks it left runnable, and
those Fallbacks tick their achievers only while their own condition (`near(goal)`)
is false. So, once moved, the subtree is skipped while any of those conditions holds:
they become children of its Fallback, right after its own condition,
`Fallback(not blocks(_, tau_goal), near(goal), ...achievers)`. The copy of the
condition left at the subtree's old place still guards the action itself.
"""

from __future__ import annotations

from btplan.bt import Fallback, Node
from btplan.model import Task
from btplan.planner import literal_of
from btplan.planner.expand import condition_node


def lineage(node: Node) -> list[Node]:
    """`node` and its ancestors, innermost first."""
    out = [node]
    while out[-1].parent is not None:
        parent = out[-1].parent
        assert parent is not None
        out.append(parent)
    return out


def scope_moved(before: list[Node], task: Task) -> list[Node]:
    """Skip the moved subtree while a condition it was moved away from holds.

    `before` is the lineage of the new subtree before conflict resolution (`lineage`).
    The node that moved is the first of it whose parent changed (the subtree, or an
    enclosing atomic BT); the Fallbacks it left are its old ancestors that are not its
    ancestors any more. Returns the condition nodes added, which are checked and
    never expanded.
    """
    for index, node in enumerate(before[:-1]):
        if node.parent is before[index + 1]:
            continue
        if not isinstance(node, Fallback) or not node.children:
            return []
        now = set(lineage(node))
        pursued = [literal_of(a.children[0]) for a in before[index + 1:]
                   if isinstance(a, Fallback) and a not in now and a.children]
        own = literal_of(node.children[0])
        present = {literal_of(c) for c in node.children}
        added: list[Node] = []
        for literal in dict.fromkeys(pursued):
            if literal is None or literal == own or literal in present:
                continue
            guard = condition_node(literal, task)
            node.insert(1 + len(added), guard)
            added.append(guard)
        return added
    return []
