"""Atomic BTs, ExpandTree (Algorithm 2) and GetConditionToExpand (Algorithm 3).

The functions here build and rewire tree nodes only; they neither tick nor look at a
world. A positive condition is a Condition leaf; a negative one (`not holding(cube)`)
is an Inverter over the Condition leaf, and that Inverter is what gets expanded.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence

from btplan.bt import FAILURE, Action, BehaviorTree, Condition, Fallback, Node
from btplan.bt import Sequence as SequenceNode
from btplan.bt.decorators import Inverter
from btplan.model import Atom, GroundAction, GroundLiteral, Task

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.classical import RelaxedModel


def condition_node(literal: GroundLiteral, task: Task) -> Node:
    """The tree leaf for a literal; ports are the predicate's parameter names."""
    atom = literal.atom
    ports = task.domain.predicate_ports.get(atom.predicate)
    if ports is not None and len(ports) != len(atom.args):
        ports = None
    leaf = Condition(atom.predicate, atom.args, ports)
    return leaf if literal.positive else Inverter(leaf)


def action_node(action: GroundAction) -> Action:
    """The tree leaf for a grounded action; its ports are the template's parameter names, so
    that an exported tree names each argument."""
    return Action(action.name, action.args, action.port_names)


def literal_of(node: Node) -> GroundLiteral | None:
    """The literal a condition node checks, or None for any other node.

    Planning reads conditions back as literals thousands of times a run (conflict
    checks read every earlier sibling's): each is made once per leaf key and sign,
    and found again by the key the leaf already holds."""
    if type(node) is Condition:
        found = _POSITIVE.get(node.key)
        return found if found is not None else _made(node, True)
    if type(node) is Inverter:
        children = node.children
        if children:
            child = children[0]
            if type(child) is Condition:
                found = _NEGATIVE.get(child.key)
                return found if found is not None else _made(child, False)
    return None


LITERALS = 1 << 16
"""Literals kept per sign (`literal_of`) before the table starts afresh: enough for any
tree, bounded for a process that plans in many problems."""

_POSITIVE: dict[tuple[str, tuple[str, ...]], GroundLiteral] = {}
_NEGATIVE: dict[tuple[str, tuple[str, ...]], GroundLiteral] = {}


def _made(leaf: Condition, positive: bool) -> GroundLiteral:
    """The literal of `leaf` with that sign, made and kept for `literal_of`."""
    table = _POSITIVE if positive else _NEGATIVE
    if len(table) >= LITERALS:
        table.clear()
    literal = table[leaf.key] = _literal(leaf.ident, leaf.args, positive)
    return literal


def _literal(predicate: str, args: tuple[str, ...], positive: bool) -> GroundLiteral:
    """GroundLiteral(Atom(predicate, args), positive), without the named tuples' Python-level
    constructors: planning reads conditions back as literals thousands of times a run."""
    return tuple.__new__(GroundLiteral, (tuple.__new__(Atom, (predicate, args)), positive))


def condition_copy(node: Node) -> Node | None:
    """A fresh plain node for the condition `node` checks or achieves, if it has one."""
    literal = literal_of(node)
    if literal is None and isinstance(node, Fallback) and node.children:
        first = node.children[0]
        literal = literal_of(first)
        node = first
    if literal is None:
        return None
    leaf = node if type(node) is Condition else node.children[0]
    assert isinstance(leaf, Condition)
    copy = Condition(leaf.ident, leaf.args, leaf.ports)
    return copy if literal.positive else Inverter(copy)


GOAL_CHECK = "all goals hold"
"""Name of the Sequence that checks every goal again at the end of a multi-goal tree."""


def initial_tree(task: Task, order: Sequence[GroundLiteral] | None = None) -> BehaviorTree:
    """Algorithm 1, lines 1-3: the goal conditions in a Sequence; one goal stands alone.

    `order` lists the goals in the order the Sequence checks them (the problem's order
    when None); the final check keeps the problem's order.

    With several goals, a last child checks them all again (named GOAL_CHECK, never
    expanded): actions may finish within the tick they start, so work for a later goal
    can undo an earlier one after it was checked, and the tree must not report SUCCESS
    then. A single goal needs no check: only its own achiever runs after it.
    """
    goals = [condition_node(g, task) for g in (order or task.goal_literals)]
    if len(goals) == 1:
        return BehaviorTree(goals[0])
    check = SequenceNode([condition_node(g, task) for g in task.goal_literals], name=GOAL_CHECK)
    return BehaviorTree(SequenceNode([*goals, check]))


def goal_check(tree: BehaviorTree) -> Node | None:
    """The final goal check of a multi-goal tree, if it has one."""
    root = tree.root
    if isinstance(root, SequenceNode) and root.children:
        last = root.children[-1]
        if isinstance(last, SequenceNode) and last.name == GOAL_CHECK:
            return last
    return None


Guards = Mapping[tuple[str, tuple[str, ...]], tuple[GroundLiteral, ...]]
"""For some achievers (by key), conditions checked first that are never expanded."""


def atomic_bt(
    condition: Node, achievers: Sequence[GroundAction], task: Task, guards: Guards | None = None
) -> Fallback:
    """Fallback(C, Sequence(pre(A1)..., A1), ...): the paper's Figure 3.

    `condition` itself becomes the first child, so it must be detached already.
    """
    alternatives: list[Node] = [condition]
    alternatives += [achiever_sequence(action, task, (guards or {}).get(action.key, ()))
                     for action in achievers]
    return Fallback(alternatives)


def achiever_sequence(
    action: GroundAction, task: Task, guards: Sequence[GroundLiteral] = ()
) -> SequenceNode:
    """Sequence(guards..., pre(A)..., A): one alternative of an atomic BT.

    A precondition written twice (`mounted(q), mounted(r)` bound with q = r) is checked
    once: a second copy would only be ticked, and expanded, twice. Guards (what the
    alternative is for, see achievers.guards) come first.
    """
    steps = [condition_node(p, task) for p in dict.fromkeys([*guards, *action.preconditions])]
    return SequenceNode([*steps, action_node(action)])


def guard_nodes(subtree: Fallback, guards: Guards) -> list[Node]:
    """The guard conditions at the head of a fallback's achiever sequences."""
    found: list[Node] = []
    for alternative in subtree.children[1:]:
        last = alternative.children[-1] if alternative.children else None
        if isinstance(alternative, SequenceNode) and isinstance(last, Action):
            found += alternative.children[: len(guards.get(last.key, ()))]
    return found


def expand_tree(
    tree: BehaviorTree, condition: Node, achievers: Sequence[GroundAction], task: Task,
    guards: Guards | None = None,
) -> Fallback:
    """Algorithm 2: replace the failed condition by its atomic BT; return the new subtree."""
    parent = condition.parent
    if parent is None:
        subtree = atomic_bt(condition, achievers, task, guards)
        tree.root = subtree
        return subtree
    index = parent.remove(condition)
    subtree = atomic_bt(condition, achievers, task, guards)
    parent.insert(index, subtree)
    return subtree


def pursued(condition: Node) -> set[GroundLiteral]:
    """The condition and every condition its ancestors' Fallbacks are trying to achieve.

    An achiever that needs one of these is circular (to hold a, clear a; to clear a,
    put a down, which needs holding a) and can never help.
    """
    goals: set[GroundLiteral] = set()
    own = literal_of(condition)
    if own is not None:
        goals.add(own)
    node = condition.parent
    while node is not None:
        if isinstance(node, Fallback) and node.children:
            first = literal_of(node.children[0])
            if first is not None:
                goals.add(first)
        node = node.parent
    return goals


def non_circular(achievers: Sequence[GroundAction], goals: Collection[GroundLiteral]
                 ) -> list[GroundAction]:
    """Achievers that need none of the conditions already being pursued above."""
    return [a for a in achievers if not circular(a, goals)]


def circular(action: GroundAction, goals: Collection[GroundLiteral]) -> bool:
    """Whether `action` needs a condition already being pursued above (by a set's own
    test, in C, when `goals` is one: `pursued` gives a set)."""
    if isinstance(goals, (set, frozenset)):
        return not goals.isdisjoint(action.preconditions)
    return any(p in goals for p in action.preconditions)


def not_through_pursued(
    achievers: Sequence[GroundAction], goals: set[GroundLiteral], relaxed: RelaxedModel,
    state: frozenset[Atom], known: Collection[str],
) -> list[GroundAction]:
    """Achievers whose preconditions can be reached without first making a pursued
    condition true (ignoring deletes).

    `non_circular` looks one step deep; this looks all the way. Holding b (pursued) by
    unstack(b, c) needs on(b, c), and with b on the table on(b, c) needs holding b: the
    achiever only runs once what it is for holds. Preconditions on values the relaxed
    model does not know (refined by a backend) are not judged.
    """
    avoided = {g.atom for g in goals if g.positive and g.atom not in state}
    if not avoided or not achievers:
        return list(achievers)
    needed = {p.atom for a in achievers for p in a.preconditions
              if p.positive and all(arg in known for arg in p.atom.args)}
    reached = relaxed.reachable_avoiding(state, avoided, needed)
    return [a for a in achievers
            if all(p.atom in reached for p in a.preconditions
                   if p.positive and p.atom in needed)]


def is_condition(node: Node) -> bool:
    """Whether `literal_of(node)` is not None, without building the literal."""
    kind = type(node)
    if kind is Condition:
        return True
    if kind is Inverter:
        children = node.children
        return bool(children) and type(children[0]) is Condition
    return False


def conditions_bfs(root: Node) -> Iterable[Node]:
    """Condition nodes in breadth-first order, left to right (GetConditionsBFS)."""
    level = [root]
    while level:
        below: list[Node] = []
        for node in level:
            if is_condition(node):
                yield node
            else:
                below += node.children
        level = below


def failed_conditions(tree: BehaviorTree, expanded: set[Node]) -> list[Node]:
    """Conditions that failed on the last tick and were not expanded yet, BFS order.

    `conditions_bfs` written out: it runs before every expansion, over the whole tree.
    """
    found: list[Node] = []
    level = [tree.root]
    while level:
        below: list[Node] = []
        for node in level:
            kind = type(node)
            if kind is Condition or (kind is Inverter and node.children
                                     and type(node.children[0]) is Condition):
                if node.status is FAILURE and node not in expanded:
                    found.append(node)
            elif kind is not Action:  # an action has no children to read
                below += node.children
        level = below
    return found


def get_condition_to_expand(tree: BehaviorTree, expanded: set[Node]) -> Node | None:
    """Algorithm 3: the first failed, not yet expanded condition in BFS order."""
    found = failed_conditions(tree, expanded)
    return found[0] if found else None
