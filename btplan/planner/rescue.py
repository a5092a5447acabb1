"""Where the last-resort search plans, and how its plan becomes part of the tree.

A condition stuck in its place (no conflict-free place, every achiever circular) is
searched for while what the earlier siblings of its Sequence ancestors hold stays
true at every step: those siblings are checked again on every tick, and a plan that
undid one would send the tree back to them. When that cannot be (the condition excludes
something held before it) or no plan is found, the condition an enclosing Fallback
pursues is tried instead, one level up at a time: the stuck part is then planned as a
whole. The plan becomes a teleo-reactive subtree (`plan_alternatives`).

When no such plan exists (Sussman's anomaly: on(b, c) cannot be made true while
on(a, b) stays true), the condition and the earlier siblings are planned together,
undoing earlier work as needed, and the earlier siblings are wrapped (`merge_plan`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from btplan.bt import BehaviorTree, Fallback, Node
from btplan.bt import Sequence as SequenceNode
from btplan.model import WILDCARD, Atom, GroundAction, GroundLiteral, Task
from btplan.planner.conflicts import guarantees, held_before, sequence_slots
from btplan.planner.expand import GOAL_CHECK, action_node, condition_node, literal_of
from btplan.grounding import wildcard_instances
from btplan.classical import Mutexes


class Engine(Protocol):
    """What plans a stuck condition: SubgoalSearch, or one over the values a world refines."""

    def search(self, start: frozenset[Atom], goal: Sequence[GroundLiteral], max_states: int = ...,
               deadline: float | None = None, keep: Sequence[GroundLiteral] = ()
               ) -> list[GroundAction] | None:
        """A plan from `start` to a state where every `goal` literal holds, no step making a
        `keep` literal false; None when none is found within `max_states` states or by
        `deadline` (a time.perf_counter() value)."""
        ...


def rescue_targets(node: Node) -> list[tuple[Node, GroundLiteral]]:
    """The stuck condition, then the conditions its enclosing Fallbacks pursue, inner first.

    Each comes with the node the plan replaces or extends: the condition itself, or
    the Fallback whose first child is the pursued condition.
    """
    own = literal_of(node)
    targets: list[tuple[Node, GroundLiteral]] = [] if own is None else [(node, own)]
    child, parent = node, node.parent
    while parent is not None:
        if isinstance(parent, Fallback) and parent.children and child is not parent.children[0]:
            pursued = literal_of(parent.children[0])
            if pursued is not None:
                targets.append((parent, pursued))
        child, parent = parent, parent.parent
    return targets


def search_goal(
    target: Node, literal: GroundLiteral, state: frozenset[Atom], mutexes: Mutexes | None
) -> list[GroundLiteral] | None:
    """`literal` and what is held before `target` and holds now; None when they exclude
    each other (a plan for the literal would then undo earlier work)."""
    goal = [literal]
    for held in held_before(target):
        if not held.holds(state) or held in goal:
            continue
        if mutexes is not None and any(mutexes.exclusive(held, g) for g in goal):
            return None
        goal.append(held)
    return goal


def regress(goal: Sequence[GroundLiteral], plan: Sequence[GroundAction],
            task: Task | None = None) -> list[list[GroundLiteral]]:
    """For each step i, what must hold before it for steps i.. to reach `goal`.

    Regression through an action drops what it makes true and adds its preconditions.
    With `task`, a wildcard negative the action makes true in part (`not blocks(_, t)`
    through putting blue aside, which deletes `blocks(blue, _)`) leaves the part it does
    not: `not blocks(o, t)` for every other cube o (`_rest`). Without it the whole
    wildcard is needed before, and a plan that clears a path is never started.
    """
    needed = list(dict.fromkeys(goal))
    out: list[list[GroundLiteral]] = []
    for action in reversed(plan):
        kept = [k for g in needed if not _achieves(action, g) for k in _rest(action, g, task)]
        needed = list(dict.fromkeys([*action.preconditions, *kept]))
        out.append(needed)
    out.reverse()
    return out


def _achieves(action: GroundAction, literal: GroundLiteral) -> bool:
    if literal.positive:
        return literal.atom in action.add
    return action.deletes(literal.atom)


def _rest(action: GroundAction, literal: GroundLiteral, task: Task | None) -> list[GroundLiteral]:
    """What of `literal` must hold before `action` so that it holds after (not achieved
    by the action as a whole): the literal itself, or the instances of a wildcard
    negative that the action's pattern deletes do not cover.

    Only where the wildcard stands for the task's objects alone: a value a world refines
    (a pose is a location) could make another instance true, and none would check it.
    """
    if task is None or literal.positive or not action.delete_patterns \
            or WILDCARD not in literal.atom.args or not _enumerable(literal, task):
        return [literal]
    instances = wildcard_instances(literal, task)
    rest = [i for i in instances if not action.deletes(i.atom)]
    return [literal] if len(rest) == len(instances) else rest


def _enumerable(literal: GroundLiteral, task: Task) -> bool:
    """Whether every object a wildcard of `literal` stands for is one of the task's: no
    refined parameter gives values of the wildcard's type."""
    domain = task.domain
    declared = domain.predicate_map[literal.atom.predicate].parameters
    wild = [p.type for a, p in zip(literal.atom.args, declared) if a == WILDCARD]
    refined = {p.type for a in domain.actions for p in a.parameters if p.refined}
    return not any(domain.is_subtype(r, w) for r in refined for w in wild)


def plan_alternatives(
    goal: Sequence[GroundLiteral], plan: Sequence[GroundAction], task: Task
) -> tuple[list[Node], list[Node]]:
    """Sequence(g_n, a_n), ..., Sequence(g_1, a_1) for a plan a_1..a_n, and their checks.

    g_i is the regression of `goal` through a_i..a_n. Behind the goal condition in a
    Fallback, the last step whose regressed condition holds runs, and each tick moves
    at least one step on (a teleo-reactive program): the plan still works if the
    world skips steps. The checks are returned so the loop never expands them (the
    plan achieves them).
    """
    checks: list[Node] = []
    alternatives: list[Node] = []
    for needed, action in reversed(list(zip(regress(goal, plan, task), plan, strict=True))):
        step = [condition_node(lit, task) for lit in needed]
        checks += step
        alternatives.append(SequenceNode([*step, action_node(action)]))
    return alternatives, checks


def insert_plan(tree: BehaviorTree, target: Node, alternatives: list[Node]) -> None:
    """Put a plan's alternatives in the tree: in a stuck condition's place, as a new
    atomic BT, or first among the achievers of a Fallback that pursues a condition."""
    if isinstance(target, Fallback):
        for offset, alternative in enumerate(alternatives, start=1):
            target.insert(offset, alternative)
        return
    parent = target.parent
    index = parent.remove(target) if parent is not None else 0
    subtree = Fallback([target, *alternatives])
    if parent is None:
        tree.root = subtree
    else:
        parent.insert(index, subtree)


def merge_slots(node: Node) -> list[tuple[SequenceNode, int, list[GroundLiteral]]]:
    """(Sequence ancestor, index, what its children up to that index guarantee), inner first.

    Only slots with earlier siblings count: they are what a plan may have to undo.
    """
    slots = []
    stuck = literal_of(node)
    for sequence, index in sequence_slots(node):
        if index == 0:
            continue
        own = guarantees(sequence.children[index]) or ([] if stuck is None else [stuck])
        earlier = [g for child in sequence.children[:index] for g in guarantees(child)]
        slots.append((sequence, index, list(dict.fromkeys([*own, *earlier]))))
    return slots


def merge_plan(
    sequence: SequenceNode, index: int, goal: Sequence[GroundLiteral],
    alternatives: list[Node], task: Task,
) -> list[Node]:
    """Fallback(all of `goal`, plan steps..., the earlier siblings as they were).

    It takes the place of the children before `index`. From the state the plan was
    found in, the plan runs (it may undo what the earlier siblings achieved) and
    leaves every goal true; from an earlier state, such as the initial one, the
    earlier siblings run as before and lead back to where the plan applies. Returns
    the new condition leaves, which the loop must not expand.
    """
    earlier = [sequence.children[i] for i in range(index)]
    for child in earlier:
        sequence.remove(child)
    checks = [condition_node(g, task) for g in goal]
    before: Node = earlier[0] if len(earlier) == 1 else SequenceNode(earlier)
    sequence.insert(0, Fallback([SequenceNode(list(checks)), *alternatives, before]))
    return checks


def plan_whole_goal(tree: BehaviorTree, task: Task, plan: Sequence[GroundAction]) -> list[Node]:
    """Sequence(Fallback(the goal tree, the plan's steps), all goals hold): the last
    resort for the whole task.

    The goal tree stays first, so the tree still says what it is for and succeeds
    where the goals hold; the plan's steps behind it are the teleo-reactive program of
    `plan_alternatives`. A step that finishes within its tick makes the Fallback
    succeed before the goal holds, so the final check (as in `initial_tree`) keeps the
    tree from reporting SUCCESS until every goal does. Returns every condition leaf
    of the new tree: none is expanded.
    """
    goals = tree.root
    goal = list(task.goal_literals)
    alternatives, _ = plan_alternatives(goal, plan, task)
    final = SequenceNode([condition_node(g, task) for g in goal], name=GOAL_CHECK)
    tree.root = SequenceNode([Fallback([goals, *alternatives]), final])
    return [n for n in tree.root.walk() if literal_of(n) is not None]


Rescued = tuple[GroundLiteral, list[GroundAction], list[Node]]
"""What a rescue planned for, the plan, and the condition leaves it added."""


class Rescuer:
    """Remembers what was searched for in one planning attempt, and plans stuck conditions.

    Each goal is searched for at most once per state. Once a condition under a
    top-level goal was rescued, the next one stuck under that goal has the goal itself
    searched for: the part already planned by search did not fit.
    """

    def __init__(self, task: Task, engine: Engine, mutexes: Mutexes | None) -> None:
        self.task = task
        self.engine = engine
        self.mutexes = mutexes
        self._searched: set[tuple[tuple[GroundLiteral, ...], frozenset[Atom]]] = set()
        self._rescued: set[GroundLiteral] = set()

    def rescue(self, tree: BehaviorTree, node: Node, state: frozenset[Atom],
               deadline: float | None) -> Rescued | None:
        """Plan `node`'s condition (or one pursued above it) and put the plan in `tree`."""
        targets = rescue_targets(node)
        if not targets:
            return None
        top = targets[-1][1]
        if top in self._rescued:
            targets = targets[-1:]  # stuck again under this goal: plan the goal as a whole
        self._rescued.add(top)
        for target, literal in targets:
            goal = search_goal(target, literal, state, self.mutexes)
            if goal is None or literal.holds(state) or not self._fresh(goal, state):
                continue
            steps = self.engine.search(state, goal, deadline=deadline, keep=goal[1:])
            if steps:
                alternatives, checks = plan_alternatives(goal, steps, self.task)
                insert_plan(tree, target, alternatives)
                return literal, steps, checks
        return self._merged(node, state, deadline)

    def _merged(self, node: Node, state: frozenset[Atom], deadline: float | None) -> Rescued | None:
        """Plan the stuck condition with its earlier siblings (`merge_plan`)."""
        for sequence, index, goal in merge_slots(node):
            if all(g.holds(state) for g in goal) or not self._fresh(goal, state):
                continue
            steps = self.engine.search(state, goal, deadline=deadline)
            if steps:
                alternatives, checks = plan_alternatives(goal, steps, self.task)
                checks += merge_plan(sequence, index, goal, alternatives, self.task)
                return goal[0], steps, checks
        return None

    def _fresh(self, goal: list[GroundLiteral], state: frozenset[Atom]) -> bool:
        """Whether `goal` was not searched for from `state` yet (and note that it is now)."""
        key = (tuple(goal), state)
        if key in self._searched:
            return False
        self._searched.add(key)
        return True
