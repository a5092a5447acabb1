"""Before an achiever runs, set up the rest of a step of another goal that it enables.

Backchaining achieves the goals one at a time, so work another goal shares with the
one under way is done twice. In logistics, the truck that fetched one package drives
back to the airport, and later drives out again for the package lying beside the first;
in blocksworld, the block taken off to clear another is put on the table, because the
block it must go onto is still covered, and is picked up again later. A plan does that
work once: it loads both packages before driving back, and clears the target before
taking the block off.

Here, when an achiever `a` is chosen, the relaxed plan for the goals still false
(h_add's cheapest producers, from the state of now) is asked for a step `b` that `a`
makes possible: `a` adds a precondition of `b`. The other preconditions of `b` that are
false now are added to `a`'s own preconditions, just before `a`, when each is one
action away now (that action can run in the state of now), is not undone by `a`, and
is not exclusive (h^2) with what `a` needs: loading the second package is one step
away while the truck stands beside it, and clearing b5 while the hand is empty. The
added conditions are expanded like any other; the step `b` itself is left to its goal.
Off in the published algorithm.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable, Sequence
from itertools import repeat

from btplan.bt import Composite, Fallback, Node
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.planner.expand import condition_node, pursued
from btplan.classical import RelaxedModel
from btplan.classical import Mutexes

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.acting.state import LoopState

_PLANS: weakref.WeakKeyDictionary[RelaxedModel, RelaxedPlans] = weakref.WeakKeyDictionary()


class RelaxedPlans:
    """The relaxed plan of the last state asked about, its steps by the false atoms
    they need: the expansions of one tick (up to a dozen at the start of a run) share
    their state, and each asks only about the atoms its achiever adds. Each atom's
    producers are taken apart once (cost, positive preconditions): the relaxed plan of
    every new state reads them again."""

    def __init__(self, relaxed: RelaxedModel) -> None:
        self._relaxed = weakref.ref(relaxed)
        """Weakly: `_PLANS` keeps this per relaxed model only while the model lives, and
        a strong reference from the value kept every run's model (and the whole grounded
        task behind it) alive for the rest of the process, for the garbage collector to
        walk through again and again."""
        self._key: tuple[frozenset[Atom], tuple[Atom, ...]] | None = None
        self._needing: dict[Atom, list[GroundAction]] = {}
        self._made_by: dict[Atom, list[Producer]] = {}

    @property
    def relaxed(self) -> RelaxedModel:
        """The relaxed model these plans are of; only weakly held, so asking after the model was
        dropped is a bug (an assertion)."""
        relaxed = self._relaxed()
        assert relaxed is not None, "asked after its relaxed model was dropped"
        return relaxed

    def producers(self, atom: Atom) -> list[Producer]:
        """The relaxed model's producers of `atom`, in its order, taken apart."""
        found = self._made_by.get(atom)
        if found is None:
            found = self._made_by[atom] = producers(self.relaxed, atom)
        return found

    def needing(self, state: frozenset[Atom], goals: Sequence[Atom]
                ) -> dict[Atom, list[GroundAction]]:
        """Atom -> the steps of the relaxed plan that need it and find it false."""
        key = (state, tuple(goals))
        if key != self._key:
            needing: dict[Atom, list[GroundAction]] = {}
            for step, needs in _plan(self.relaxed.costs(state), state, goals, self.producers):
                for atom in needs:
                    if atom not in state:
                        needing.setdefault(atom, []).append(step)
            self._key, self._needing = key, needing
        return self._needing


Producer = tuple[GroundAction, float, tuple[Atom, ...]]
"""A producer, its cost and its positive preconditions (in order, repeats kept)."""


def producers(relaxed: RelaxedModel, atom: Atom) -> list[Producer]:
    """`atom`'s producers in the relaxed model's order, each with its cost and positive
    preconditions: the parts the relaxed plan reads for every state."""
    return [(a, a.cost, a.needs)
            for a in relaxed.producers(atom)]


def prepare_before(loop: LoopState, subtree: Fallback, action: GroundAction,
                   condition: GroundLiteral, state: frozenset[Atom], optional: set[Node],
                   plans: RelaxedPlans) -> list[Node]:
    """Add the conditions `prepared` finds to the new subtree's first alternative; the
    ones to expand. Not within a prepared condition's own subtree (`optional` holds
    them): preparing there goes round (the truck's return prepares unloading the
    plane, whose unloading prepares the truck's return)."""
    if _within(subtree, optional):
        return []
    found = prepared(action, condition, loop.task.goal_literals, plans, loop.index.mutexes,
                     state)
    if not found:
        return []
    taken = pursued(subtree.children[0])
    extra = [(c, m) for c, m in found if c not in taken]
    wanted, skips = insert_before_action(subtree, extra, loop.task, action)
    loop.never_expand(skips)
    return wanted


def relaxed_plans(relaxed: RelaxedModel) -> RelaxedPlans:
    """The relaxed plans of a relaxed model, shared by every loop of that model (while
    one of them keeps a reference)."""
    plans = _PLANS.get(relaxed)
    if plans is None:
        plans = _PLANS[relaxed] = RelaxedPlans(relaxed)
    return plans


def on_the_way(plans: RelaxedPlans, state: frozenset[Atom], goals: Sequence[Atom],
               atom: Atom) -> bool:
    """Whether the relaxed plan for `goals` from `state` makes `atom` true on its way:
    a step needs it and it is false (the plan is not kept: `needing` keeps the open
    goals' plan for `prepared`)."""
    if atom in state:
        return False
    steps = _plan(plans.relaxed.costs(state), state, goals, plans.producers)
    return any(atom in needs for _, needs in steps)


def _within(start: Node, optional: set[Node]) -> bool:
    """Whether `start` is a prepared condition's subtree or lies inside one."""
    node: Node | None = start
    while node is not None:
        if node in optional or (isinstance(node, Fallback) and node.children
                                and node.children[0] in optional):
            return True
        node = node.parent
    return False


def relaxed_plan(relaxed: RelaxedModel, state: frozenset[Atom],
                 goals: Sequence[Atom]) -> list[GroundAction]:
    """The steps of a relaxed plan for `goals` from `state`: for each atom needed and
    false, its cheapest producer by h_add (the first on ties), and that producer's
    preconditions in turn."""
    return [step for step, _ in _plan(relaxed.costs(state), state, goals,
                                      lambda atom: producers(relaxed, atom))]


def _plan(cost: dict[Atom, float], state: frozenset[Atom], goals: Sequence[Atom],
          made_by: Callable[[Atom], list[Producer]]
          ) -> list[tuple[GroundAction, tuple[Atom, ...]]]:
    """relaxed_plan's steps, each with its positive preconditions, from the h_add
    costs of `state` and each atom's producers."""
    inf = math.inf
    get, infinite = cost.get, repeat(inf)
    chosen: dict[tuple[str, tuple[str, ...]], tuple[GroundAction, tuple[Atom, ...]]] = {}
    seen: set[Atom] = set()
    todo = [g for g in goals if g not in state]
    while todo:
        atom = todo.pop()
        if atom in seen or atom in state:
            continue
        seen.add(atom)
        best: GroundAction | None = None
        best_needs: tuple[Atom, ...] = ()
        best_cost = inf
        floor = get(atom, inf)  # h_add's own value: no producer does better
        for producer, own, needs in made_by(atom):
            value = own + sum(map(get, needs, infinite))  # get(p, inf) for each p
            if value < best_cost:  # ties: the first, in the model's fixed order
                best, best_needs, best_cost = producer, needs, value
                if value <= floor:
                    break
        if best is None:
            continue
        chosen.setdefault(best.key, (best, best_needs))
        todo.extend(best_needs)
    return list(chosen.values())


def prepared(action: GroundAction, condition: GroundLiteral,
             goals: Sequence[GroundLiteral], plans: RelaxedPlans, mutexes: Mutexes,
             state: frozenset[Atom]) -> list[tuple[GroundLiteral, GroundAction]]:
    """Conditions to achieve before `action`, for a step of another goal it enables,
    each with the grounding that achieves it in one step from `state`."""
    open_goals = [g.atom for g in goals if g.positive and not g.holds(state)]
    if not open_goals or not action.add:
        return []
    needing = plans.needing(state, open_goals)
    enabled = {step.key: step for atom in action.add for step in needing.get(atom, ())
               if step.key != action.key}
    if not enabled:
        return []
    needs = [p for p in action.preconditions if p.positive]
    out: dict[GroundLiteral, GroundAction] = {}
    for step in enabled.values():
        for pre in step.preconditions:
            if not pre.positive:
                continue
            if (pre.atom in state or pre.atom in action.add or pre in out
                    or pre == condition or action.deletes(pre.atom)):
                continue
            if any(mutexes.exclusive(pre, need) for need in (*needs, condition)
                   if need.positive):
                continue
            maker = _one_step(plans.producers(pre.atom), state)
            if maker is not None:
                out[pre] = maker
    return list(out.items())


def _one_step(made_by: list[Producer], state: frozenset[Atom]) -> GroundAction | None:
    """A grounding among an atom's producers that can run in `state` (positive
    preconditions)."""
    for producer, _, needs in made_by:
        if all(p in state for p in needs):
            return producer
    return None


def insert_before_action(subtree: Fallback,
                         conditions: Sequence[tuple[GroundLiteral, GroundAction]],
                         task: Task, action: GroundAction | None = None,
                         ) -> tuple[list[Node], list[Node]]:
    """Put each condition into the subtree's first alternative, just before its action,
    as `Fallback(condition, not p1, ..., not pk)` with p1..pk the preconditions of the
    one step that makes it: once that step cannot run (another agent took the package
    away), the condition is passed over instead of pursued from farther. Preconditions
    it shares with `action` need no guard: the alternative checks them first. Returns
    the conditions to expand and the guards, which are checked and never expanded."""
    first = subtree.children[1] if len(subtree.children) > 1 else None
    if not conditions or not isinstance(first, Composite) or not first.children:
        return [], []
    at = len(first.children) - 1
    shared = set(action.preconditions) if action is not None else set()
    wanted: list[Node] = []
    guards: list[Node] = []
    for literal, maker in conditions:
        node = condition_node(literal, task)
        skip = [condition_node(GroundLiteral(p.atom, False), task)
                for p in maker.preconditions if p.positive and p not in shared]
        first.insert(at, Fallback([node, *skip]))
        at += 1
        wanted.append(node)
        guards += skip
    return wanted, guards


def give_up(node: Node) -> bool:
    """Take a prepared condition (its guarded Fallback) out of the tree, when it has no
    achiever or no conflict-free place: it was an extra, never a need."""
    holder = node.parent
    if not isinstance(holder, Fallback) or not isinstance(holder.parent, Composite):
        return False
    holder.parent.remove(holder)
    return True
