"""Offline planning's executed plan made shorter, and a tree that runs the shorter plan.

Once backchaining (or the last resort) has a tree whose run from the initial state
reaches the goal, btplan/classical/improvement.py looks for a shorter plan within a share of
the time. The user gets the plan (`--plan-out`) and the tree, and both must agree: the
shorter plan goes into the tree ahead of the backchained tree, as the teleo-reactive
steps the last resort's plans become (`rescue.plan_alternatives`, with what
consecutive steps share checked once: `shared_first`):

    Retry(Sequence(Fallback(the goals hold, step n, ..., step 1, the backchained tree),
                   all goals hold))

From the initial state the latest step whose regressed condition holds runs, so the
tree executes the shorter plan (or skips ahead where the world lets it); where no
step fits, as after an outside change, the backchained tree acts as before. The tree
is then run once from the initial state, and what that run executes is the plan
reported: when it is not shorter, the backchained tree and its plan stay as they were.
"""

from __future__ import annotations

import time
from bisect import bisect_left
from collections.abc import Callable, Iterable, Sequence

from btplan.bt import FAILURE, SUCCESS, BehaviorTree, Fallback, Node, Retry
from btplan.bt import Sequence as SequenceNode
from btplan.model import GroundAction, GroundLiteral, Task
from btplan.planner import AchieverIndex, condition_node
from btplan.planner.expand import GOAL_CHECK, action_node
from btplan.planner.plan_first import IMPROVED, UNTIL_DONE
from btplan.classical import Improvement, improve
from btplan.classical import Limits, PlanSpace
from btplan.classical import PackedActions
from btplan.collector import building
from btplan.records import record
from btplan.worlds.symbolic import SymbolicWorld

MIN_SECONDS = 0.25
"""Seconds the improvement may take however fast planning was (within the time limit)."""

PLANNING_SHARE = 0.25
"""Beyond MIN_SECONDS, the improvement may take this share of the time planning took."""

LEFT_SHARE = 0.5
"""It never takes more than this share of the time left before the deadline: the tree
still has to be run and written."""

MIN_LEFT = 1.0
"""Seconds that must be left before the deadline for the improvement to start at all:
putting a plan into the tree and running it is not bounded by the budget."""

SEARCH_SHARE = 0.75
"""The share of the improvement's time the search gets; putting the plan into the tree
and running it from the start take the rest."""

PACKED_BYTES = 64 << 20
"""The most memory the grounded actions packed as bit masks may take for the
neighbourhood search (an estimate: `packed_for`)."""


def budget(started: float, now: float, deadline: float | None) -> float:
    """Seconds the improvement may take, planning having run from `started` to `now`."""
    seconds = max(MIN_SECONDS, PLANNING_SHARE * (now - started))
    if deadline is not None:
        left = deadline - now
        seconds = min(seconds, LEFT_SHARE * left) if left >= MIN_LEFT else 0.0
    return seconds


@record
class Improved:
    """The tree with the shorter plan ahead, what it executed, and how it was found."""

    tree: BehaviorTree
    executed: list[GroundAction]
    ticks: int
    found: Improvement


def improve_executed(
    task: Task, models: AchieverIndex, tree: BehaviorTree, executed: Sequence[GroundAction],
    seed: int, seconds: float, stop: Callable[[], bool] | None = None, floor: int = 0,
) -> Improved | None:
    """A shorter plan than `executed`, ahead of `tree`; None when none is found within
    about `seconds` or when `stop` says to stop. `floor`: no plan has fewer steps."""
    until = time.perf_counter() + SEARCH_SHARE * seconds
    with building():
        packed, whole = packed_for(models, executed)
        space = PlanSpace(packed, frozenset(task.initial_state), task.goal_literals)
        states = Limits.states_for(len(packed.atoms)) if whole else 0
        found = improve(space, executed, Limits(states, until, stop), floor)
    if found is None:
        return None
    improved = plan_first(tree, task, found.steps)
    run = run_from_start(improved, task, seed, found.steps)
    if run is None or _measure(run[0]) >= _measure(executed):
        undo_plan_first(improved)
        return None
    return Improved(improved, run[0], run[1], found)


def packed_for(models: AchieverIndex, executed: Sequence[GroundAction]
               ) -> tuple[PackedActions, bool]:
    """Every grounded action as bit masks, and True; or, where those would take more
    than PACKED_BYTES, only the plan's actions, and False (action elimination needs no
    others; the neighbourhood search is then left out).

    Each action's masks are ints as long as its highest atom number: a 100-block
    blocksworld's 20,000 actions over 10,000 atoms took about 110 MB, and 200 blocks
    would take 16 times that."""
    if models.has_packed or models.packed_bytes <= PACKED_BYTES:
        return models.packed, True
    own = {a.key: a for a in executed if not a.delete_patterns}
    return PackedActions(list(own.values())), False


def plan_first(tree: BehaviorTree, task: Task, steps: Sequence[GroundAction]) -> BehaviorTree:
    """A new tree: the steps of `steps` ahead of `tree`'s root (see the module's text)."""
    from btplan.planner.rescue import regress  # only when a plan got shorter

    order = Latest(steps)
    goal = order.before(task.goal_literals, len(steps))
    changing = {e.predicate for a in task.domain.actions for e in a.effects}
    numbered = [(i, [g for g in needed if g.atom.predicate in changing
                     or g in action.preconditions], action)
                for i, (needed, action) in enumerate(zip(regress(goal, steps), steps, strict=True))]
    alternatives = shared_first(numbered[::-1], frozenset(), task, order)
    holds: Node = (condition_node(goal[0], task) if len(goal) == 1
                   else SequenceNode([condition_node(g, task) for g in goal]))
    final = SequenceNode([condition_node(g, task) for g in goal], name=GOAL_CHECK)
    ahead = Fallback([holds, *alternatives, tree.root], name=IMPROVED)
    return BehaviorTree(Retry(SequenceNode([ahead, final]), attempts=2 * len(steps) + 1,
                              name=UNTIL_DONE))


class Latest:
    """Orders conditions by the last step that made them true, latest first.

    A tick checks the steps' conditions from the last step back; of what a later step
    needs, the condition made true latest before it is the one most likely still
    false, so a step that cannot run yet is passed over after one check instead of a
    whole list of goals."""

    def __init__(self, steps: Sequence[GroundAction]) -> None:
        self.made: dict[GroundLiteral, list[int]] = {}
        for number, action in enumerate(steps):
            for atom in action.delete:
                self.made.setdefault(GroundLiteral(atom, False), []).append(number)
            for atom in action.add:
                self.made.setdefault(GroundLiteral(atom, True), []).append(number)

    def before(self, literals: Iterable[GroundLiteral], step: int) -> list[GroundLiteral]:
        """`literals` (each once), those made true latest before `step` first."""

        def last(literal: GroundLiteral) -> int:
            made = self.made.get(literal, ())
            at = bisect_left(made, step)
            return made[at - 1] if at else -1

        return sorted(dict.fromkeys(literals), key=lambda g: -last(g))


GROUPS = 4
"""Parts a run of steps is split into, each checking once what all of its steps need."""

Step = tuple[int, list[GroundLiteral], GroundAction]
"""A plan step: its number, what must hold before it (the regressed goal), its action."""


def shared_first(steps: list[Step], held: frozenset[GroundLiteral], task: Task, order: Latest
                 ) -> list[Node]:
    """The alternatives Sequence(g_i, a_i) of `rescue.plan_alternatives` for `steps`
    (last step first), with what consecutive steps all need checked once.

    Each g_i lists every goal reached before step i, so the flat alternatives grow with
    steps times goals (a 338-step visit-all plan: 43,000 conditions). `plan_first`
    already leaves out of g_i what no action changes (`connected(x, y)`), but for the
    preconditions of step i itself: it holds whenever the plan could run. Here the steps
    are split into GROUPS parts, recursively; a part becomes Sequence(what all its
    steps need, Fallback(its steps)), and its steps leave out what the part checks.
    A Fallback of such parts picks the same step as the flat one: g_i holds exactly
    when its part's shared conditions and its own rest hold. `held`: what enclosing
    parts check already.
    """
    if len(steps) <= GROUPS:
        return [SequenceNode([*(condition_node(g, task) for g in order.before(needed, number)
                                if g not in held), action_node(action)])
                for number, needed, action in steps]
    size = -(-len(steps) // GROUPS)
    out: list[Node] = []
    for start in range(0, len(steps), size):
        part = steps[start:start + size]
        later = [set(needed) for _, needed, _ in part[1:]]
        shared = [g for g in part[0][1] if g not in held and all(g in n for n in later)]
        inner = shared_first(part, held | frozenset(shared), task, order)
        if shared:
            earliest = part[-1][0]
            out.append(SequenceNode([*(condition_node(g, task)
                                       for g in order.before(shared, earliest)),
                                     Fallback(inner)]))
        else:
            out.extend(inner)
    return out


def undo_plan_first(improved: BehaviorTree) -> None:
    """Detach the backchained tree's root again from a tree `plan_first` made."""
    ahead = improved.root.children[0].children[0]
    assert isinstance(ahead, Fallback)
    ahead.remove(ahead.children[-1])


def run_from_start(tree: BehaviorTree, task: Task, seed: int,
                   steps: Sequence[GroundAction]) -> tuple[list[GroundAction], int] | None:
    """(the actions `tree` executes from the initial state, ticks) until it succeeds;
    None when it fails, or takes more ticks than `steps` needs."""
    world = SymbolicWorld(task, seed=seed, groundings={a.key: a for a in steps})
    limit = sum(max(1, a.duration) for a in steps) + 1
    for tick in range(1, limit + 1):
        status = tree.tick(world)
        if status is SUCCESS:
            return list(world.executed), tick
        if status is FAILURE:
            break
    tree.halt(world)
    return None


def _measure(plan: Sequence[GroundAction]) -> tuple[float, int]:
    return sum(a.cost for a in plan), len(plan)
