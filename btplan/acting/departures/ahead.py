"""Looking ahead along an action's preconditions before the robot starts acting.

A Sequence ticks its children left to right and stops at the first that fails, so
Algorithm 1 only ever sees the first false precondition of an action. When a later
one is false too, the robot first achieves the earlier one, and finds the later one
false only then: in blocksworld it picks up the block to stack, then finds the target
covered, and (since unstacking needs an empty hand) puts the block down again. Seeing
the later conditions false in the same state, before anything runs, lets conflict
resolution order the subtrees as a plan would, and costs no tick of the world.

One level further, the same happens to the achiever a later condition gets: carrying
the cube to the goal needs `near(goal)`, whose MoveTo needs the path free, and freeing
it needs the hand the cube is about to fill. The tick meets that only with the cube in
hand, and sets it down again. So the false preconditions of that achiever are looked
at too (`deeper_false`), and expanded at once when every achiever they would get
conflicts with what is held before the action they are for (`forced_out`), unless
the relaxed plan for what is held passes through them: conflict resolution then puts
them in front, as it does for the later conditions themselves. Those that fit where
they stand are left for the tick to reach, as before.
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence

from btplan.bt import Fallback, Node
from btplan.bt import Sequence as SequenceNode
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner import Judge, literal_of
from btplan.planner.conflicts import falsifies, guarantees, sequence_slots


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
    if not isinstance(parent, SequenceNode):
        return []
    return _false(parent.children[parent.index_of(node) + 1:], state, expanded)


def deeper_false(node: Node, state: frozenset[Atom], expanded: Collection[Node]) -> list[Node]:
    """The preconditions of the achiever `node` was just expanded with (the first
    alternative of its atomic BT) that do not hold in `state` and are not expanded."""
    holder = node.parent
    if not isinstance(holder, Fallback) or len(holder.children) < 2:
        return []
    first = holder.children[1]
    if not isinstance(first, SequenceNode):
        return []
    return _false(first.children, state, expanded)


def _false(nodes: Sequence[Node], state: frozenset[Atom], expanded: Collection[Node]) -> list[Node]:
    out = []
    for node in nodes:
        literal = literal_of(node)
        if literal is not None and node not in expanded and not literal.holds(state):
            out.append(node)
    return out


def forced_out(node: Node, achievers: Sequence[GroundAction], judge: Judge,
               reached_first: Callable[[list[GroundLiteral]], bool] | None = None) -> bool:
    """Whether every one of `achievers`, run for a precondition of `node`'s achiever,
    needs a condition that an earlier sibling along `node`'s Sequences excludes, or
    makes one false: conflict resolution's rules (a) and (b), asked before the atomic
    BT is built. Then what that sibling holds (the cube in hand) would have to be given
    up to achieve the precondition.

    The achiever's own other preconditions are not counted: the look-ahead orders
    them when the first of them is expanded (`later_false`); nor a sibling whose
    conditions `reached_first` says are reached only through the precondition's
    (clearing b4 is on the way to stacking b3 onto b6 when b3 lies under b4):
    achieving that sibling achieves the precondition first."""
    if not achievers:
        return False
    earlier = [(guarantees(e), e) for sequence, index in sequence_slots(node)
               for e in sequence.children[:index] if e not in judge.guards]
    first: dict[int, bool] = {}

    def gives_up(action: GroundAction) -> bool:
        needs = [list(action.preconditions)]
        for number, (held, sibling) in enumerate(earlier):
            if not (judge.blocked(held, needs, sibling)
                    or any(falsifies(action, h) for h in held)):
                continue
            if reached_first is not None:
                if number not in first:
                    first[number] = reached_first(held)
                if first[number]:
                    continue
            return True
        return False

    return bool(earlier) and all(gives_up(a) for a in achievers)
