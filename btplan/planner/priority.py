"""IncreasePriority and the search for a conflict-free place (Algorithm 1, lines 11-12).

The paper moves the new subtree one place left, and when it is leftmost, before its
parent. Only a Sequence slot keeps the meaning "do this first", so "before its parent"
climbs to the nearest enclosing Sequence (a Fallback slot would make the subtree an
alternative). A subtree that leaves its Sequence leaves a plain copy of its condition
behind, so the action that needed it still checks it right before running.

When the paper's positions are all in conflict, btplan tries more places before
giving up (docs/design/planner-05-more-places.md says why and what it buys):
  1. the paper's positions for the new subtree N;
  2. the same for each enclosing atomic BT of N, innermost first (reordering goals);
  3. the front of the achiever sequence of an earlier sibling X, for those enclosing
     atomic BTs and then for N: "make this true while achieving X", which, unlike a
     slot before X, is not re-checked once X holds.
A place of step 3 is refused when it is circular (conflicts.circular_place): there the
moved subtree runs only while the condition X pursues is false, and cannot succeed
before it holds. The judge carries what that check needs only when goals may be
reordered.
"""

from __future__ import annotations

from collections.abc import Callable

from btplan.bt import BehaviorTree, Composite, Fallback, Node
from btplan.bt import Sequence as SequenceNode
from btplan.errors import UnresolvableConflictError
from btplan.planner.conflicts import (
    Conflict,
    Judge,
    alternative_conflicts,
    circular_place,
    earlier_work,
    find_conflicts,
    has_conflicts,
    placement_conflicts,
)
from btplan.planner.expand import condition_copy, literal_of
from btplan.records import record

Slot = tuple[Composite, int]
Undo = Callable[[], None]


@record(frozen=True, slots=True)
class Resolution:
    """What conflict resolution did: the conflicts found first and the moves made."""

    conflicts: tuple[Conflict, ...]
    moves: int


def paper_slots(node: Node) -> list[Slot]:
    """The places IncreasePriority visits, in order: left, then before the parent, up."""
    slots: list[Slot] = []
    parent = node.parent
    if isinstance(parent, SequenceNode):
        slots += [(parent, i) for i in range(parent.index_of(node) - 1, -1, -1)]
    child: Node | None = parent
    above = parent.parent if parent is not None else None
    while above is not None:
        if isinstance(above, SequenceNode) and child is not None:
            slots += [(above, i) for i in range(above.index_of(child), -1, -1)]
        child, above = above, above.parent
    return slots


def nested_slots(node: Node) -> list[Slot]:
    """The fronts of the first achiever sequence of every earlier sibling, nearest first."""
    slots: list[Slot] = []
    child: Node = node
    above = node.parent
    while above is not None:
        if isinstance(above, SequenceNode):
            for earlier in reversed(above.children[: above.index_of(child)]):
                if isinstance(earlier, Fallback) and len(earlier.children) > 1:
                    first = earlier.children[1]
                    if isinstance(first, SequenceNode):
                        slots.append((first, 0))
        child, above = above, above.parent
    return slots


def move_to(node: Node, slot: Slot) -> Undo:
    """Put `node` at `slot`; a node leaving its Sequence leaves its condition's copy.

    Returns the function that puts everything back as it was.
    """
    parent = node.parent
    assert parent is not None, "only a node with a parent can be moved"
    home = parent.index_of(node)
    target, index = slot
    parent.remove(node)
    copy: Node | None = None
    if target is not parent:
        copy = condition_copy(node)
        if copy is not None:
            parent.insert(home, copy)
    target.insert(index, node)

    def undo() -> None:
        target.remove(node)
        if copy is not None:
            parent.remove(copy)
        parent.insert(home, node)

    return undo


def increase_priority(tree: BehaviorTree, subtree: Node) -> bool:
    """One step of the paper's IncreasePriority; False when there is no earlier slot."""
    del tree  # the root never moves: the paper's tree has its goals at the top
    slots = paper_slots(subtree)
    if not slots:
        return False
    move_to(subtree, slots[0])
    return True


def resolve_conflicts(
    tree: BehaviorTree,
    subtree: Node,
    judge: Judge,
    reorder_goals: bool = True,
    prune: bool = True,
) -> Resolution:
    """Move `subtree` (or, failing that, an enclosing subtree) until nothing conflicts.

    Alternatives of the new atomic BT that conflict are dropped first when others do
    not; see the module docstring for the order places are tried in. Raises
    UnresolvableConflictError naming the conflicts when no place is free of them.
    """
    del tree
    first = tuple(find_conflicts(subtree, judge))
    if not first:
        return Resolution((), 0)
    if prune and prune_conflicting_alternatives(subtree, judge) and not has_conflicts(
        subtree, judge
    ):
        return Resolution(first, 0)
    enclosing = [a for a in _ancestors(subtree) if isinstance(a, Fallback) and a.parent]
    plans: list[tuple[Node, list[Slot], bool]] = [(subtree, paper_slots(subtree), False)]
    if reorder_goals:
        plans += [(a, paper_slots(a), False) for a in enclosing]
        plans += [(a, nested_slots(a), True) for a in enclosing]
        plans += [(subtree, nested_slots(subtree), True)]
    for mover, slots, nested in plans:
        for number, slot in enumerate(slots, start=1):
            undo = move_to(mover, slot)
            if _settled(subtree, mover, judge) and not (nested and circular_place(mover, judge)):
                return Resolution(first, number)
            undo()
    listed = "; ".join(sorted({str(c) for c in first}))
    raise UnresolvableConflictError(
        f"no conflict-free place for the subtree achieving {_label(subtree)}: {listed}"
    )


def prune_conflicting_alternatives(subtree: Node, judge: Judge) -> bool:
    """Drop the alternatives of a new atomic BT that conflict where it stands.

    Only while at least one alternative is left. Alternatives that conflict inside the
    subtree's own Sequence go first: moving the subtree cannot help them, and they could
    only run once that Sequence has failed. Then, if some alternatives are free of
    conflicts, the others go: a fallback keeps the ways that work here rather than
    being moved for the ones that do not (the paper moves the whole subtree).
    """
    if not isinstance(subtree, Fallback) or len(subtree.children) < 3:
        return False
    pruned = False
    earlier = earlier_work(subtree, judge)  # the alternatives share their place
    for depth in (1, None):
        alternatives = subtree.children[1:]
        bad = [a for a in alternatives
               if alternative_conflicts(subtree, a, judge, depth, earlier)]
        if bad and len(bad) < len(alternatives):
            for alternative in bad:
                subtree.remove(alternative)
            pruned = True
    return pruned


def _settled(subtree: Node, mover: Node, judge: Judge) -> bool:
    if has_conflicts(subtree, judge) or placement_conflicts(mover, judge):
        return False
    return mover is subtree or not has_conflicts(mover, judge)


def _ancestors(node: Node) -> list[Node]:
    out: list[Node] = []
    current = node.parent
    while current is not None:
        out.append(current)
        current = current.parent
    return out


def _label(subtree: Node) -> str:
    literal = literal_of(subtree.children[0]) if subtree.children else None
    return str(literal) if literal is not None else subtree.name
