"""Watching the way ahead of the running actions for conditions an outside change broke.

Algorithm 1 expands a condition when a tick fails on it, and a reactive Sequence only
reaches a condition once everything before it succeeds. So when an external agent
breaks a condition that the robot needs later (Example 2: the sphere rolls onto the
path to the goal while the robot fetches the cube), the tree notices only when the
robot gets there: it fetches the cube, finds the path blocked, drops the cube, clears
the path and fetches the cube again. A replanner checks its whole plan on every tick
and clears the path first.

Here, on a tick after an outside change, the loop looks along the path of the running
actions at what is still to come, and asks where the tree would fail if it got there in
the state of now. When that place is a condition the outside change made false and that
has no subtree yet, it is expanded at once, as the tick that reaches it would expand
it, and conflict resolution puts the new subtree where it belongs before the robot goes
on. Conditions that were false before the change are left to the tick that reaches
them: the work under way may well be what makes them true.
"""

from __future__ import annotations

from collections.abc import Collection

from btplan.bt import FAILURE, RUNNING, SUCCESS, Action, Fallback, Node, Sequence, Status
from btplan.model import Atom
from btplan.planner import literal_of

Outcome = Status | list[Node]
"""What ticking a subtree in the state of now would do, if every action it starts ran to
success: SUCCESS; RUNNING (it would start or keep an action); or fail, given as the
unexpanded conditions there in the order Algorithm 3 picks them ([]: none to expand)."""


def broken_ahead(root: Node, state: frozenset[Atom], before: frozenset[Atom],
                 expanded: Collection[Node]) -> tuple[list[Node], int]:
    """Unexpanded conditions ahead of the running actions that would make the tree fail
    when it got to them, and that held in `before` but not in `state`; with the number
    of conditions looked at (what the watch costs in monitoring).

    Only while the tree would keep running those actions: when the change sends it
    elsewhere (an earlier goal undone, a moved subtree that now has work to do), it is
    reacting already, and what lies ahead is looked at again once it comes back.
    """
    look = _Look(state, expanded)
    found: list[Node] = []
    for action in _running(root):
        if look.kept(action):
            found.extend(n for n in look.first_blocked(action) if _broken(n, state, before))
    return list(dict.fromkeys(found)), look.checks


def _running(root: Node) -> list[Action]:
    """The actions left RUNNING by the last tick."""
    return [n for n in root.walk() if isinstance(n, Action) and n.status is RUNNING]


def _broken(node: Node, state: frozenset[Atom], before: frozenset[Atom]) -> bool:
    literal = literal_of(node)
    return literal is not None and literal.holds(before) and not literal.holds(state)


class _Look:
    """Ticks the tree in thought: in `state`, every action started runs to success."""

    def __init__(self, state: frozenset[Atom], expanded: Collection[Node]) -> None:
        self.state, self.expanded = state, expanded
        self.checks = 0

    def kept(self, action: Action) -> bool:
        """Whether the next tick would reach `action` again: up its ancestors, everything
        before it in a Sequence succeeds, and everything before it in a Fallback fails."""
        child: Node = action
        parent = action.parent
        while parent is not None:
            if not isinstance(parent, (Sequence, Fallback)):
                return False  # a node the loop did not build: no telling what it ticks
            wanted = SUCCESS if isinstance(parent, Sequence) else FAILURE
            for sibling in parent.children[:parent.children.index(child)]:
                outcome = self.outcome(sibling)
                if (FAILURE if isinstance(outcome, list) else outcome) is not wanted:
                    return False
            child, parent = parent, parent.parent
        return True

    def first_blocked(self, action: Action) -> list[Node]:
        """Where the tree would first fail after `action`: up its Sequences, the later
        siblings."""
        child: Node = action
        parent = action.parent
        while parent is not None:
            if isinstance(parent, Sequence):
                for sibling in parent.children[parent.children.index(child) + 1:]:
                    outcome = self.outcome(sibling)
                    if isinstance(outcome, list):
                        return outcome  # the Sequence stops there: nothing after is reached
            child, parent = parent, parent.parent
        return []

    def outcome(self, node: Node) -> Outcome:
        """What ticking `node` would do (see Outcome)."""
        literal = literal_of(node)
        if literal is not None:
            self.checks += 1
            if literal.holds(self.state):
                return SUCCESS
            return [] if node in self.expanded else [node]
        if isinstance(node, Fallback):
            first: list[Node] | None = None
            for child in node.children:
                outcome = self.outcome(child)
                if not isinstance(outcome, list):
                    return outcome
                if first is None and child is not node.children[0]:
                    first = outcome
            return first if first is not None else []
        if isinstance(node, Sequence):
            ran = False
            for child in node.children:
                outcome = self.outcome(child)
                if isinstance(outcome, list):
                    return outcome
                ran = ran or outcome is RUNNING
            return RUNNING if ran else SUCCESS
        return RUNNING  # an action, or a node the loop did not build: assume it runs
