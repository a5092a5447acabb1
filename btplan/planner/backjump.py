"""Which achiever choice to give up when a planning attempt fails (`retry_choices`).

Backchaining commits, at every expansion, to a ranked handful of achievers (and to
their bindings: which hand, which truck). When an attempt later stops (no
conflict-free place, a dead end, a loop), the paper has no way back. btplan starts
the attempt over with one choice banned: a (condition, grounded action) pair that
the next attempt never uses for that condition, so the condition's next-ranked
achievers take its place. Which pair: the achiever sequence whose earlier
preconditions keep the stuck subtree from every place (its action needs something
that excludes what comes after), else the achiever sequences enclosing the stuck
condition, innermost first, each in turn on later failures (backjumping upwards when
the inner condition has nothing else left).

The functions here only read trees; the loop records the culprits, and
btplan.acting.offline.plan bans them one per attempt.
"""

from __future__ import annotations

from btplan.bt import Action, Fallback, LeafKey, Node
from btplan.bt import Sequence as SequenceNode
from btplan.model import GroundLiteral
from btplan.planner.conflicts import Judge, achiever_leaves, guarantees, sequence_slots
from btplan.planner.expand import literal_of

Choice = tuple[GroundLiteral, LeafKey]
"""A condition and the key of a grounded action chosen to achieve it."""


def achiever_choice(node: Node) -> Choice | None:
    """(condition, action key) when `node` is an achiever sequence under its condition."""
    if not isinstance(node, SequenceNode) or not node.children:
        return None
    last = node.children[-1]
    parent = node.parent
    if not isinstance(last, Action) or not isinstance(parent, Fallback):
        return None
    if not parent.children or parent.children[0] is node:
        return None
    literal = literal_of(parent.children[0])
    return None if literal is None else (literal, last.key)


def enclosing_choices(node: Node) -> list[Choice]:
    """The achiever sequences `node` sits in, innermost first."""
    found: list[Choice] = []
    current: Node | None = node
    while current is not None:
        choice = achiever_choice(current)
        if choice is not None:
            found.append(choice)
        current = current.parent
    return found


def conflict_choices(subtree: Node, judge: Judge) -> list[Choice]:
    """Achiever sequences in which an earlier precondition conflicts with `subtree`
    where it stands (rules (a) and (b)), innermost first, then the enclosing ones."""
    found: list[Choice] = []
    own = achiever_leaves(subtree)
    for sequence, index in sequence_slots(subtree):
        for earlier in sequence.children[:index]:
            if earlier in judge.guards:
                continue
            held = guarantees(earlier)
            if judge.blocks(held, subtree, achiever_leaves(earlier), "") or judge.threatens(
                    own, held, ""):
                choice = achiever_choice(sequence)
                if choice is not None:
                    found.append(choice)
                break
    return list(dict.fromkeys([*found, *enclosing_choices(subtree)]))


def running_choices(tree_root: Node, key: LeafKey) -> list[Choice]:
    """The achiever sequences ending in the action `key` (the one a loop keeps running)."""
    found: list[Choice] = []
    for node in tree_root.walk():
        if isinstance(node, Action) and node.key == key and node.parent is not None:
            found += enclosing_choices(node.parent)
    return list(dict.fromkeys(found))
