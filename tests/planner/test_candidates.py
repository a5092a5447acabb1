"""Achievers read from the static bindings are the achievers enumerated afresh.

`AchieverIndex.achievers` takes the groundings that the static checks allow from the
relaxed model (btplan/planner/candidates.py) instead of enumerating bindings on every
look-up. These tests compare it, condition by condition and state by state, with an
index that always enumerates, including in the cases where the table must step aside:
static facts that changed, more bindings than `max_bindings`, `where` constraints on
predicates that actions change, refined parameters.
"""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest

from btplan.acting.offline import load
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.planner.achievers import ALL
from btplan.planner.candidates import StaticBindings

ROOT = Path(__file__).resolve().parents[2]
TASKS = {
    "towers": ("bench/problems/blocksworld_6.bt",),
    "packages": ("bench/problems/logistics_1.bt",),
    "obstacle": ("domains/pick_place_obstacle.bt",),
    "swap": ("domains/planner_swap.bt",),
}

GUARDED = """
domain guarded {
    types { room  item }
    constants { lamp : item }
    predicates {
        door(a: room, b: room)
        open(a: room, b: room)
        at(r: room)
        has(i: item)
        lies(i: item, r: room)
    }
    action go(a: room, b: room) {
        where: door(a, b), open(a, b)
        pre: at(a)
        post: not at(a), at(b)
    }
    action take(i: item, r: room) {
        pre: at(r), lies(i, r)
        post: has(i), not lies(i, r)
    }
    action restore(i: item, r: room) {
        pre: at(r), has(i), has(lamp)
        post: lies(i, r), not has(i)
    }
    action unlock(a: room, b: room) {
        where: door(a, b), not open(a, b)
        pre: at(a)
        post: open(a, b)
    }
}
problem guarded_1 for guarded {
    objects { r1, r2, r3, r4 : room  key, map : item }
    init {
        at(r1)
        door(r1, r2), door(r2, r3), door(r3, r4), door(r2, r1), door(r3, r2)
        open(r1, r2), open(r2, r3)
        lies(key, r3), lies(map, r4)
    }
    goal { has(key) }
}
"""


def _enumerating(task: Task, options: PlannerOptions) -> AchieverIndex:
    """An index that never reads the table: the reference."""
    index = AchieverIndex(task, options)
    index.static.pick = lambda *args, **kwargs: None  # type: ignore[method-assign]
    return index


def _states(task: Task, index: AchieverIndex, count: int, seed: int) -> list[frozenset[Atom]]:
    """States met on a random walk from the initial state (actions that can run there)."""
    rng = random.Random(seed)
    state = task.initial_state
    states = [state]
    names = {t.name for t in task.domain.actions if not any(p.refined for p in t.parameters)}
    actions = [a for a in index.relaxed.actions if a.name in names]
    for _ in range(count):
        runnable = [a for a in actions if a.applicable(state)]
        if not runnable:
            break
        state = rng.choice(runnable).apply(state)
        states.append(state)
    return states


def _conditions(task: Task, index: AchieverIndex, state: frozenset[Atom]) -> list[GroundLiteral]:
    atoms = {a for action in index.relaxed.actions for a in action.add} | set(state)
    atoms |= {g.atom for g in task.goal_literals}
    ordered = sorted(atoms)
    return [GroundLiteral(a, True) for a in ordered] + [GroundLiteral(a, False) for a in ordered]


def _same_achievers(task: Task, options: PlannerOptions, states: list[frozenset[Atom]],
                    refine: Any = None) -> int:
    tabled = AchieverIndex(task, options)
    tabled.relaxed  # noqa: B018 (built, so that the table is read)
    reference = _enumerating(task, options)
    compared = 0
    for state in states:
        for condition in _conditions(task, tabled, state):
            mine = tabled.achievers(condition, state, refine, ALL)
            theirs = reference.achievers(condition, state, refine, ALL)
            assert [str(a) for a in mine] == [str(a) for a in theirs], (condition, sorted(state))
            compared += bool(mine)
    return compared


@pytest.mark.parametrize("name", sorted(TASKS))
def test_the_table_finds_the_achievers_enumeration_finds(name: str) -> None:
    task = load(*(str(ROOT / f) for f in TASKS[name]))
    options = PlannerOptions()
    states = _states(task, AchieverIndex(task, options), 12, seed=len(name))
    assert _same_achievers(task, options, states) > 0


@pytest.mark.parametrize("prune", [True, False])
def test_without_the_heuristic_the_answers_agree_too(prune: bool) -> None:
    """Without h_add every achiever is kept, also one whose preconditions are out of
    reach: then only pruning (the table's reachability check) drops it."""
    task = load(str(ROOT / TASKS["towers"][0]))
    options = PlannerOptions(prune_bindings=prune, heuristic=False, mutexes=False)
    states = _states(task, AchieverIndex(task), 8, seed=3)
    assert _same_achievers(task, options, states) > 0


def test_more_bindings_than_the_limit_are_left_to_enumeration() -> None:
    """Which bindings enumeration keeps then depends on its order: the table steps aside."""
    task = load(str(ROOT / TASKS["towers"][0]))
    options = PlannerOptions(max_bindings=2)
    index = AchieverIndex(task, options)
    index.relaxed  # noqa: B018
    hand = GroundLiteral(Atom("hand_empty", ()), True)
    # put_down(x) and stack(x, y) for any held x: more than two bindings each
    way = index.static.ways(hand, [(t, i, e) for t in task.domain.actions
                                   for i, e in enumerate(t.effects)
                                   if e.predicate == "hand_empty" and e.positive])[0]
    assert index.static.pick(way, task.initial_state, None, 2, index.relaxed.actions,
                             lambda action: True) is None
    assert _same_achievers(task, options, _states(task, index, 8, seed=5)) > 0


def test_a_changed_static_fact_sends_every_look_up_back_to_enumeration(tmp_path: Path) -> None:
    """An agent may add or remove a fact no action changes (a door walled up)."""
    (tmp_path / "guarded.bt").write_text(GUARDED)
    task = load(str(tmp_path / "guarded.bt"))
    options = PlannerOptions()
    index = AchieverIndex(task, options)
    index.relaxed  # noqa: B018
    walled = task.initial_state - {Atom("door", ("r2", "r3"))}
    extra = task.initial_state | {Atom("door", ("r4", "r1"))}
    at_r3 = GroundLiteral(Atom("at", ("r3",)), True)
    effects = [(t, i, e) for t in task.domain.actions for i, e in enumerate(t.effects)
               if e.predicate == "at" and e.positive]
    way = index.static.ways(at_r3, effects)[0]
    always = lambda action: True  # noqa: E731
    assert index.static.pick(way, task.initial_state, None, 64, index.relaxed.actions,
                             always) is not None
    for state in (walled, extra):
        assert index.static.pick(way, state, None, 64, index.relaxed.actions, always) is None
    assert _same_achievers(task, options, [walled, extra, task.initial_state]) > 0


def test_the_static_verdict_follows_a_walk_of_states(tmp_path: Path) -> None:
    """The verdict carried from one state to the next while only changing facts differ
    must turn when a static fact goes, stay turned while it is gone, and turn back."""
    (tmp_path / "guarded.bt").write_text(GUARDED)
    task = load(str(tmp_path / "guarded.bt"))
    index = AchieverIndex(task)
    index.relaxed  # noqa: B018
    door = Atom("door", ("r2", "r3"))
    opened = Atom("open", ("r3", "r4"))
    walk = [(task.initial_state, True), (task.initial_state | {opened}, True),
            ((task.initial_state | {opened}) - {door}, False),
            (task.initial_state - {door}, False), (task.initial_state - {door}, False),
            (task.initial_state, True), (task.initial_state | {Atom("door", ("r4", "r1"))}, False),
            (task.initial_state | {opened}, True)]
    at_r3 = GroundLiteral(Atom("at", ("r3",)), True)
    effects = [(t, i, e) for t in task.domain.actions for i, e in enumerate(t.effects)
               if e.predicate == "at" and e.positive]
    way = index.static.ways(at_r3, effects)[0]
    for state, usable in walk:
        picked = index.static.pick(way, frozenset(state), None, 64, index.relaxed.actions,
                                   lambda action: True)
        assert (picked is not None) is usable


def test_where_constraints_on_changing_facts_are_checked_in_each_state(tmp_path: Path) -> None:
    """go needs the door open and unlock needs it shut, in the state of the look-up."""
    (tmp_path / "guarded.bt").write_text(GUARDED)
    task = load(str(tmp_path / "guarded.bt"))
    index = AchieverIndex(task)
    states = _states(task, index, 10, seed=1)
    opened = task.initial_state | {Atom("open", ("r3", "r4"))}
    for options in (PlannerOptions(), PlannerOptions(heuristic=False)):
        assert _same_achievers(task, options, [*states, opened]) > 0
    # lies(key, r1) never comes back once taken: take(key, r1) is pruned, not ranked
    has_key = GroundLiteral(Atom("has", ("key",)), True)
    plain = AchieverIndex(task, PlannerOptions(heuristic=False))
    assert [str(a) for a in plain.achievers(has_key, task.initial_state, None, ALL)] == [
        "take(key, r3)"]
    at_r4 = GroundLiteral(Atom("at", ("r4",)), True)
    before = [str(a) for a in index.achievers(at_r4, task.initial_state, None, ALL)]
    after = [str(a) for a in index.achievers(at_r4, opened, None, ALL)]
    assert "go(r3, r4)" not in before and "go(r3, r4)" in after


def test_one_table_serves_every_index_of_the_task() -> None:
    task = load(str(ROOT / TASKS["packages"][0]))
    first = AchieverIndex(task)
    second = AchieverIndex(task, PlannerOptions(max_alternatives=2), like=first)
    assert isinstance(first.static, StaticBindings) and second.static is first.static


def test_one_step_back_agrees_with_the_relaxed_search(tmp_path: Path) -> None:
    """keep_reachable's shortcut says yes only where the relaxed search says yes too (and
    no where taking an item leaves nothing to put it back)."""
    from btplan.planner.lookahead import _back_in_one_step

    (tmp_path / "guarded.bt").write_text(GUARDED)
    tasks = [load(*(str(ROOT / f) for f in TASKS[n])) for n in ("towers", "packages", "obstacle")]
    said_yes = said_no = 0
    for task in [*tasks, load(str(tmp_path / "guarded.bt"))]:
        index = AchieverIndex(task)
        relaxed = index.relaxed
        for state in _states(task, index, 8, seed=7):
            for action in relaxed.actions:
                after = action.apply(state)
                lost = state - after
                if _back_in_one_step(lost, after, relaxed):
                    said_yes += 1
                    assert relaxed.reachable(after, lost), (action, sorted(state))
                else:
                    said_no += 1
    assert said_yes > 0 and said_no > 0


@pytest.mark.parametrize("name", sorted(TASKS))
def test_dropping_circular_achievers_before_ranking_changes_nothing(name: str) -> None:
    """`achievers_avoiding` drops the achievers that need a pursued condition before
    ranking them: the list and the verdict "all were circular" are those of ranking all
    and dropping after."""
    from btplan.planner.expand import non_circular

    task = load(*(str(ROOT / f) for f in TASKS[name]))
    options = PlannerOptions()
    index = AchieverIndex(task, options)
    rng = random.Random(7)
    all_circular = kept = 0
    for state in _states(task, index, 8, seed=len(name) + 1):
        conditions = _conditions(task, index, state)
        needed = sorted({p for a in index.relaxed.actions for p in a.preconditions})
        for condition in conditions:
            pursued = {condition, *rng.sample(needed, min(3, len(needed)))}
            ranked = index.achievers(condition, state, None, ALL)
            expected = non_circular(ranked, pursued)
            mine, circular = index.achievers_avoiding(condition, state, None, pursued)
            assert [str(a) for a in mine] == [str(a) for a in expected], condition
            assert circular == (bool(ranked) and not expected), condition
            all_circular += circular
            kept += bool(mine)
    assert kept > 0
    if name == "towers":
        assert all_circular > 0  # stack(b, c) for on(b, c) needs holding(b), often drawn
