"""Conflicts and IncreasePriority (Algorithm 1, lines 11-12).

A subtree placed in a Sequence runs only once every earlier sibling succeeded, that is
while each earlier sibling's condition holds (the paper: "the new subtree will be
executed if and only if h = c holds"). So, for the new subtree N and each earlier
sibling X along N's chain of Sequence ancestors, there is a conflict when

  (a) an action that achieves X's condition also makes a condition N needs false
      (Pick(cube) achieves holding(cube) and deletes hand_empty, which N needs), or
  (b) an action of N makes X's condition false: N would undo what an earlier part
      achieved and still relies on.

IncreasePriority moves N one place left; when N is leftmost it goes before its
parent. Only a Sequence slot keeps the meaning "do this first", so "before its
parent" climbs to the nearest enclosing Sequence (a Fallback slot would turn N into an
alternative). Once N has moved, it must also not break what now follows it:

  (c) an action achieving a later sibling's condition must not make N's condition false,
  (d) an action of N must not make a condition a later sibling needs false.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from btplan.bt import Action, BehaviorTree, Composite, Fallback, LeafKey, Node
from btplan.bt import Sequence as SequenceNode
from btplan.errors import UnresolvableConflictError
from btplan.model import GroundAction, GroundLiteral
from btplan.planner.expand import literal_of

Grounding = Mapping[LeafKey, GroundAction]


@dataclass(frozen=True, slots=True)
class Conflict:
    """An action whose effect makes a condition false where the tree relies on it."""

    action: str
    condition: str
    rule: str

    def __str__(self) -> str:
        return f"{self.action} makes {self.condition} false ({self.rule})"


# --- what a subtree guarantees, needs and does ---------------------------------------------


def guarantees(node: Node) -> list[GroundLiteral]:
    """Literals that hold once `node` succeeded: its condition, or its children's."""
    literal = literal_of(node)
    if literal is not None:
        return [literal]
    if isinstance(node, Fallback) and node.children:
        first = literal_of(node.children[0])
        return [first] if first is not None else []
    if isinstance(node, SequenceNode):
        return [g for child in node.children for g in guarantees(child)]
    return []


def achiever_leaves(node: Node) -> list[Action]:
    """The actions that directly achieve `node`'s condition (last child of each alternative)."""
    if isinstance(node, Action):
        return [node]
    if isinstance(node, Fallback):
        out: list[Action] = []
        for child in node.children[1:]:
            if isinstance(child, Action):
                out.append(child)
            elif isinstance(child, SequenceNode) and child.children:
                last = child.children[-1]
                if isinstance(last, Action):
                    out.append(last)
        return out
    if isinstance(node, SequenceNode):
        return [a for child in node.children for a in achiever_leaves(child)]
    return []


def requirements(node: Node) -> list[GroundLiteral]:
    """Conditions `node` needs to do its work: the preconditions in its alternatives."""
    literal = literal_of(node)
    if literal is not None:
        return [literal]
    if isinstance(node, Fallback):
        needs: list[GroundLiteral] = []
        for child in node.children[1:]:
            if isinstance(child, SequenceNode):
                needs.extend(g for c in child.children[:-1] for g in guarantees(c))
        return needs
    if isinstance(node, SequenceNode):
        return [g for child in node.children for g in guarantees(child)]
    return []


def falsifies(action: GroundAction, literal: GroundLiteral) -> bool:
    if literal.positive:
        return action.deletes(literal.atom)
    return literal.atom in action.add


def _clashes(
    doers: list[Action], conditions: list[GroundLiteral], grounding: Grounding, rule: str
) -> list[Conflict]:
    found: list[Conflict] = []
    for leaf in doers:
        action = grounding.get(leaf.key)
        if action is None:
            continue
        for literal in conditions:
            if falsifies(action, literal):
                found.append(Conflict(str(action), str(literal), rule))
    return found


# --- finding conflicts ---------------------------------------------------------------------


def _sequence_slots(node: Node) -> list[tuple[SequenceNode, int]]:
    """(Sequence ancestor, index of the child that contains `node`), innermost first."""
    slots: list[tuple[SequenceNode, int]] = []
    child = node
    parent = node.parent
    while parent is not None:
        if isinstance(parent, SequenceNode):
            slots.append((parent, parent.index_of(child)))
        child, parent = parent, parent.parent
    return slots


def find_conflicts(subtree: Node, grounding: Grounding) -> list[Conflict]:
    """Rules (a) and (b) for `subtree` where it stands now."""
    needs = requirements(subtree)
    own = achiever_leaves(subtree)
    found: list[Conflict] = []
    for sequence, index in _sequence_slots(subtree):
        for earlier in sequence.children[:index]:
            found += _clashes(achiever_leaves(earlier), needs, grounding, "an earlier action")
            found += _clashes(own, guarantees(earlier), grounding, "undoes earlier work")
    return found


def placement_conflicts(moved: Node, grounding: Grounding) -> list[Conflict]:
    """Rules (c) and (d) for a subtree that was moved before some siblings."""
    parent = moved.parent
    if not isinstance(parent, SequenceNode):
        return []
    index = parent.index_of(moved)
    kept = guarantees(moved)
    own = achiever_leaves(moved)
    found: list[Conflict] = []
    for later in parent.children[index + 1 :]:
        found += _clashes(achiever_leaves(later), kept, grounding, "a later action")
        found += _clashes(own, requirements(later), grounding, "breaks later work")
    return found


# --- moving subtrees -----------------------------------------------------------------------


def increase_priority(tree: BehaviorTree, subtree: Node) -> bool:
    """Move `subtree` one step earlier; False when no earlier Sequence slot exists."""
    parent = subtree.parent
    if isinstance(parent, SequenceNode):
        index = parent.index_of(subtree)
        if index > 0:
            parent.remove(subtree)
            parent.insert(index - 1, subtree)
            return True
    child: Node | None = parent
    above = parent.parent if parent is not None else None
    while above is not None and not isinstance(above, SequenceNode):
        child, above = above, above.parent
    if above is None or child is None or parent is None:
        return False
    parent.remove(subtree)
    above.insert(above.index_of(child), subtree)
    return True


@dataclass(frozen=True, slots=True)
class Resolution:
    """What conflict resolution did: the conflicts found first and the moves made."""

    conflicts: tuple[Conflict, ...]
    moves: int


def resolve_conflicts(
    tree: BehaviorTree, subtree: Node, grounding: Grounding, reorder_goals: bool = True
) -> Resolution:
    """Algorithm 1, lines 11-12: move `subtree` left until the tree is free of conflicts.

    Positions are tried in the paper's order. If none is free of conflicts and
    `reorder_goals` is on, the subtree goes back and an enclosing subtree is moved
    left instead (reordering sibling goals, which solves Sussman's anomaly). If that
    fails too, UnresolvableConflictError names the conflicts.
    """
    first = tuple(find_conflicts(subtree, grounding))
    if not first:
        return Resolution((), 0)
    if prune_conflicting_alternatives(subtree, grounding) and not find_conflicts(
        subtree, grounding
    ):
        return Resolution(first, 0)
    home = _position(subtree)
    moves = 0
    while increase_priority(tree, subtree):
        moves += 1
        if not find_conflicts(subtree, grounding) and not placement_conflicts(subtree, grounding):
            return Resolution(first, moves)
    _restore(subtree, home)
    if reorder_goals:
        moved = _reorder_enclosing(subtree, grounding)
        if moved:
            return Resolution(first, moved)
    listed = "; ".join(sorted({str(c) for c in first}))
    raise UnresolvableConflictError(
        f"no conflict-free place for the subtree achieving {subtree.children[0].name}: {listed}"
        if isinstance(subtree, Composite) and subtree.children
        else f"no conflict-free place for {subtree.name}: {listed}"
    )


def prune_conflicting_alternatives(subtree: Node, grounding: Grounding) -> bool:
    """Drop the alternatives of a new atomic BT that conflict where it stands.

    Only when at least one alternative is free of conflicts: a fallback keeps every
    way that works here rather than moving all of them (a departure from the paper,
    which moves the whole subtree; see docs/planner.md).
    """
    if not isinstance(subtree, Fallback) or len(subtree.children) < 3:
        return False
    bad = [alt for alt in subtree.children[1:] if _alternative_conflicts(subtree, alt, grounding)]
    if not bad or len(bad) == len(subtree.children) - 1:
        return False
    for alt in bad:
        subtree.remove(alt)
    return True


def _alternative_conflicts(subtree: Fallback, alternative: Node, grounding: Grounding) -> bool:
    needs = [g for c in alternative.children[:-1] for g in guarantees(c)]
    own = [c for c in alternative.children[-1:] if isinstance(c, Action)]
    for sequence, index in _sequence_slots(subtree):
        for earlier in sequence.children[:index]:
            if _clashes(achiever_leaves(earlier), needs, grounding, ""):
                return True
            if _clashes(own, guarantees(earlier), grounding, ""):
                return True
    return False


def _position(node: Node) -> tuple[Composite, int]:
    parent = node.parent
    assert parent is not None, "a subtree with a conflict has a Sequence ancestor"
    return parent, parent.index_of(node)


def _restore(node: Node, home: tuple[Composite, int]) -> None:
    if node.parent is not None:
        node.parent.remove(node)
    parent, index = home
    parent.insert(index, node)


def _reorder_enclosing(subtree: Node, grounding: Grounding) -> int:
    """Move an ancestor of `subtree` left in its Sequence until nothing conflicts.

    Innermost ancestor first; each is put back where it was if no place works.
    """
    ancestor = subtree.parent
    while ancestor is not None and ancestor.parent is not None:
        sequence = ancestor.parent
        if isinstance(sequence, SequenceNode):
            home = sequence.index_of(ancestor)
            for index in range(home - 1, -1, -1):
                sequence.remove(ancestor)
                sequence.insert(index, ancestor)
                if not find_conflicts(subtree, grounding) and not placement_conflicts(
                    ancestor, grounding
                ):
                    return home - index
            sequence.remove(ancestor)
            sequence.insert(home, ancestor)
        ancestor = sequence
    return 0
