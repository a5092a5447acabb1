"""h_FF's relaxed plans and the landmark estimate of the last-resort search.

h_FF is checked against a plain reference that runs the same exploration without its
shortcuts (no early stop, a set test instead of counters): the same value and the same
relaxed plan on every state looked at, and that plan, replayed with deletes ignored,
reaches the goal. The landmark orders (`SubgoalSearch.landmark_orders`) are checked on
Sussman's anomaly. Counts only, never times.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from btplan.acting.offline import load
from btplan.model import Task
from btplan.planner import AchieverIndex
from btplan.classical.packed import INFINITE, PackedActions, bits
from tests.planner.shapes import DOMAINS, atom, generated


def reference_h_ff(packed: PackedActions, true: list[int], goals: list[int]
                   ) -> tuple[float, set[int]]:
    """h_FF written plainly: atoms taken first in, first out; an action fires when its
    last precondition is taken; each atom keeps the first action that adds it; the
    exploration runs to the end; the plan is extracted from the goals back."""
    supporter: dict[int, int] = {a: -1 for a in true}
    queue = list(true)
    fired = set()
    for i, pre in enumerate(packed.pre):
        if not pre:
            fired.add(i)
            for a in packed.add[i]:
                if a not in supporter:
                    supporter[a] = i
                    queue.append(a)
    head = 0
    while head < len(queue):
        taken = set(queue[:head + 1])
        for i in packed.by_pre[queue[head]]:
            if i not in fired and set(packed.pre[i]) <= taken:
                fired.add(i)
                for a in packed.add[i]:
                    if a not in supporter:
                        supporter[a] = i
                        queue.append(a)
        head += 1
    if any(g not in supporter for g in goals):
        return INFINITE, set()
    plan: set[int] = set()
    todo = list(goals)
    while todo:
        i = supporter[todo.pop()]
        if i >= 0 and i not in plan:
            plan.add(i)
            todo.extend(packed.pre[i])
    return float(len(plan)), plan


def states(packed: PackedActions, start: int, count: int) -> list[int]:
    """`count` states reached from `start` breadth first (all true atoms as bits)."""
    seen, queue = [start], [start]
    while queue and len(seen) < count:
        state = queue.pop(0)
        for i in packed.applicable(state, bits(state)):
            child = packed.apply(i, state)
            if child not in seen:
                seen.append(child)
                queue.append(child)
    return seen[:count]


@pytest.mark.parametrize(("name", "size"), [
    ("blocksworld", {"blocks": 5}), ("gripper", {"balls": 3}), ("logistics", {"packages": 2}),
])
def test_h_ff_equals_the_plain_reference_and_its_plan_reaches_the_goal(
        tmp_path: Path, name: str, size: dict[str, int]) -> None:
    task = generated(tmp_path, name, 0, **size)
    engine = AchieverIndex(task).subgoal_search
    packed = engine.packed
    goals = engine.begin(task.initial_state, task.goal_literals).numbers
    looked = 0
    for state in states(packed, packed.encode(task.initial_state), 40):
        true = bits(state)
        h, plan = packed.h_ff(true, goals)
        assert (h, plan) == reference_h_ff(packed, true, goals)
        runnable = [i for i in range(len(packed.actions))
                    if state & packed.pre_mask[i] == packed.pre_mask[i]
                    and not state & packed.neg_mask[i]]  # by first precondition, then number
        runnable.sort(key=lambda i: (bool(packed.pre[i]), packed.pre[i][:1], i))
        assert packed.applicable(state, true) == runnable
        if h == INFINITE:
            continue
        looked += 1
        reached = set(true)  # the plan, replayed with deletes ignored, reaches the goal
        waiting = set(plan)
        while waiting:
            ready = {i for i in waiting if set(packed.pre[i]) <= reached}
            assert ready, "a relaxed plan action never becomes applicable"
            for i in ready:
                reached.update(packed.add[i])
            waiting -= ready
        assert set(goals) <= reached
    assert looked > 10


def test_an_unreachable_goal_is_infinite_and_a_held_goal_costs_nothing() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))  # c on a; a and b on the table
    packed = AchieverIndex(task).subgoal_search.packed
    start = packed.encode(task.initial_state)
    held = [packed.ids[atom("on(c, a)")]]
    assert packed.h_ff(bits(start), held) == (0.0, set())
    h, plan = packed.h_ff([], [packed.ids[atom("on(a, b)")]])  # nothing true: no hand
    assert h == INFINITE and not plan
    h, plan = packed.h_ff(bits(start), [packed.ids[atom("on(a, b)")]])
    assert h == 3  # unstack c, pick up a, stack it
    assert {str(packed.actions[i]) for i in plan} == {"unstack(c, a)", "pickup(a)",
                                                       "stack(a, b)"}


def test_a_landmark_every_achiever_of_another_needs_is_ordered_before_it() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    packed = AchieverIndex(task).subgoal_search.packed
    start = packed.encode(task.initial_state)
    goal = [packed.ids[atom("on(a, b)")]]
    every = packed.landmarks(bits(start), goal)
    needed = packed.necessary(every)
    ids = packed.ids
    # Stacking a on b needs a held and b clear; holding a needs a clear.
    assert needed[ids[atom("on(a, b)")]] == (1 << ids[atom("holding(a)")]
                                             | 1 << ids[atom("clear(b)")])
    assert needed[ids[atom("holding(a)")]] >> ids[atom("clear(a)")] & 1
    assert ids[atom("clear(c)")] not in needed or not needed[ids[atom("clear(c)")]] \
        >> ids[atom("holding(a)")] & 1


def sussman_with_orders() -> tuple[Task, PackedActions, Any]:
    """Sussman's anomaly, a search run begun with the landmark orders on."""
    task = load(str(DOMAINS / "planner_sussman.bt"))
    engine = AchieverIndex(task).subgoal_search
    engine.landmark_orders = True
    return task, engine.packed, engine.begin(task.initial_state, task.goal_literals)


def test_a_landmark_reached_then_lost_counts_again_while_a_later_one_needs_it(
        tmp_path: Path) -> None:
    task, packed, run = sussman_with_orders()
    start = packed.encode(task.initial_state)
    passed = run.progress(run.before_start, start)
    base = run.count(start, passed)
    clear = 1 << packed.ids[atom("clear(a)")]
    # A state where the path made clear(a) true once, and then lost it (as when c is
    # put back on a): the count is one higher than with clear(a) still true.
    assert run.marks & clear
    kept = run.count(start | clear, passed | clear)
    lost = run.count(start & ~clear, passed | clear)
    assert lost == kept + 1
    assert base == kept + 1  # never reached: counted once, as missing


def test_a_goal_reached_before_a_landmark_that_undoes_it_is_not_counted_yet(
        tmp_path: Path) -> None:
    # Sussman: on(a, b) and on(b, c). Stacking b on c needs b held, which b under a
    # forbids: on(b, c) comes before on(a, b), and on(a, b) reached first is no progress.
    task, packed, run = sussman_with_orders()
    ids = packed.ids
    a_on_b, b_on_c = ids[atom("on(a, b)")], ids[atom("on(b, c)")]
    before = dict(run.orders)[a_on_b]
    assert before >> b_on_c & 1
    start = packed.encode(task.initial_state)
    state = start | 1 << a_on_b
    passed = run.before_start | (before & ~(1 << b_on_c))  # all but on(b, c) passed
    assert not run.progress(passed, state) >> a_on_b & 1
    assert run.progress(passed | 1 << b_on_c, state) >> a_on_b & 1
    assert run.progress(passed, state | 1 << b_on_c) >> a_on_b & 1
