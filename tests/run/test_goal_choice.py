"""Goal-aware achiever choice (btplan.acting.departures.credit, btplan.acting.departures.prepare): the detours
that choosing one goal at a time makes, and that the btplan method no longer makes."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from btplan import run
from btplan.acting import ACTING_OPTIONS
from btplan.acting.departures.credit import credit_goals
from btplan.acting.departures.prepare import (
    RelaxedPlans,
    give_up,
    insert_before_action,
    prepared,
    relaxed_plan,
)
from btplan.acting.offline import load
from btplan.bt import Action, Fallback, Sequence
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex
from btplan.planner.expand import atomic_bt, condition_node
from btplan.classical.heuristic import RelaxedModel
from tests.presets import departures

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OPTIONS = replace(ACTING_OPTIONS, expansions_per_tick=64)

DETOUR = """
problem detour for blocksworld {
    objects { b1, b2, b3, b4, b5 : block }
    init {
        on_table(b3) on(b4, b3) clear(b4)
        on_table(b5) on(b2, b5) clear(b2)
        on_table(b1) clear(b1) hand_empty
    }
    goal { on(b3, b1) on(b4, b5) }
}
"""
"""b4 must come off b3 and go onto b5, which b2 covers: a plan clears b5 first."""

ONE_TRIP = """
problem one_trip for logistics {
    objects {
        city1 : city
        city1_airport : airport
        city1_loc1 : location
        truck1 : truck
        pkg1, pkg2 : package
    }
    init {
        in_city(city1_airport, city1) in_city(city1_loc1, city1)
        at(truck1, city1_airport) at(pkg1, city1_loc1) at(pkg2, city1_loc1)
    }
    goal { at(pkg1, city1_airport) at(pkg2, city1_airport) }
}
"""
"""Both packages lie at the same place: a plan fetches them in one trip."""


def task_of(tmp_path: Path, domain: str, problem: str, name: str) -> Task:
    path = tmp_path / f"{name}.bt"
    path.write_text(problem)
    return load(str(DOMAINS / domain), str(path), problem=name)


def executed(task: Task, goal_credit: bool) -> list[str]:
    outcome = run(task, config=departures(OPTIONS, look_ahead=True, scope_moves=True,
                                          goal_credit=goal_credit))
    assert outcome.reached
    return [str(a) for a in outcome.world.executed]


def test_the_block_goes_onto_its_target_instead_of_the_table(tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    old = executed(task, goal_credit=False)
    new = executed(task, goal_credit=True)
    assert "put_down(b4)" in old and "pick_up(b4)" in old  # the detour
    assert new == ["unstack(b2, b5)", "put_down(b2)", "unstack(b4, b3)", "stack(b4, b5)",
                   "pick_up(b3)", "stack(b3, b1)"]
    assert len(new) < len(old)


def test_the_truck_loads_both_packages_before_driving_back(tmp_path: Path) -> None:
    task = task_of(tmp_path, "logistics.bt", ONE_TRIP, "one_trip")
    old = executed(task, goal_credit=False)
    new = executed(task, goal_credit=True)
    drives = [a for a in new if a.startswith("drive_truck")]
    assert len(drives) == 2 and len(new) == 6
    assert len([a for a in old if a.startswith("drive_truck")]) == 4
    assert new.index("load_truck(pkg2, truck1, city1_loc1)") < new.index(
        "drive_truck(truck1, city1_loc1, city1_airport, city1)")


def _index(task: Task) -> AchieverIndex:
    return AchieverIndex(task, OPTIONS)


def test_credit_ranks_the_achiever_that_makes_a_goal_true_first(tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = _index(task)
    state = frozenset({Atom("holding", ("b4",)), Atom("on_table", ("b3",)),
                       Atom("clear", ("b3",)), Atom("on_table", ("b5",)),
                       Atom("clear", ("b5",)), Atom("on_table", ("b1",)),
                       Atom("clear", ("b1",)), Atom("on_table", ("b2",)),
                       Atom("clear", ("b2",))})
    hand = GroundLiteral(Atom("hand_empty", ()), True)
    ranked = index.achievers(hand, state, None, 8)
    assert str(ranked[0]) == "put_down(b4)"  # cheapest on its own
    again = credit_goals(ranked, hand, task.goal_literals, index.relaxed, state)
    assert str(again[0]) == "stack(b4, b5)"
    assert {a.key for a in again} == {a.key for a in ranked}


def test_credit_leaves_the_order_when_no_achiever_makes_a_goal(tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = _index(task)
    state = task.initial_state
    literal = GroundLiteral(Atom("clear", ("b3",)), True)
    ranked = index.achievers(literal, state, None, 8)
    assert credit_goals(ranked, literal, task.goal_literals, index.relaxed, state) == ranked


def test_clearing_the_target_is_prepared_before_taking_the_block_off(tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = _index(task)
    state = task.initial_state
    clear_b3 = GroundLiteral(Atom("clear", ("b3",)), True)
    unstack = next(a for a in index.achievers(clear_b3, state, None, 8)
                   if str(a) == "unstack(b4, b3)")
    found = prepared(unstack, clear_b3, task.goal_literals, RelaxedPlans(index.relaxed),
                     index.mutexes, state)
    assert [(str(c), str(m)) for c, m in found] == [("clear(b5)", "unstack(b2, b5)")]


def test_a_prepared_condition_is_guarded_and_given_up_whole(tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = _index(task)
    state = task.initial_state
    clear_b3, clear_b5 = (GroundLiteral(Atom("clear", (b,)), True) for b in ("b3", "b5"))
    unstack = next(a for a in index.achievers(clear_b3, state, None, 8)
                   if str(a) == "unstack(b4, b3)")
    maker = next(a for a in index.achievers(clear_b5, state, None, 8)
                 if str(a) == "unstack(b2, b5)")
    subtree = atomic_bt(condition_node(clear_b3, task), [unstack], task)
    wanted, guards = insert_before_action(subtree, [(clear_b5, maker)], task, unstack)
    alternative = subtree.children[1]
    assert isinstance(alternative, Sequence)
    assert isinstance(alternative.children[-1], Action)  # still last
    holder = alternative.children[-2]
    assert isinstance(holder, Fallback) and holder.children[0] is wanted[0]
    assert len(guards) == 2  # not on(b2, b5), not clear(b2); hand_empty is checked before
    assert not give_up(alternative.children[0])  # a precondition of its own: kept
    assert give_up(wanted[0])
    assert holder not in alternative.children and len(alternative.children) == 4


def _needing_uncached(relaxed: RelaxedModel, state: frozenset[Atom],
                      goals: list[Atom]) -> dict[Atom, list[str]]:
    needing: dict[Atom, list[str]] = {}
    for step in relaxed_plan(relaxed, state, goals):
        for p in step.preconditions:
            if p.positive and p.atom not in state:
                needing.setdefault(p.atom, []).append(str(step))
    return needing


def test_the_kept_relaxed_plan_and_producers_match_computing_them_afresh(tmp_path: Path) -> None:
    """RelaxedPlans keeps each atom's producers taken apart and the last state's plan:
    along a run of the detour, in every state met (and back to an earlier one), what it
    answers is what the relaxed model gives when asked afresh."""
    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = _index(task)
    plans = RelaxedPlans(index.relaxed)
    goals = [g.atom for g in task.goal_literals]
    states = [task.initial_state]
    for name in ("unstack(b2, b5)", "put_down(b2)", "unstack(b4, b3)"):
        step = next(a for a in index.relaxed.actions if str(a) == name)
        states.append(step.apply(states[-1]))
    asked = 0
    for state in [*states, states[0], states[0]]:
        got = {atom: [str(s) for s in steps]
               for atom, steps in plans.needing(state, goals).items()}
        assert got == _needing_uncached(index.relaxed, state, goals)
        asked += bool(got)
        for atom in got:
            assert [p for p, _, _ in plans.producers(atom)] == index.relaxed.producers(atom)
    assert asked >= 3  # the plan had steps to compare in most states


def test_a_runs_relaxed_model_is_freed_once_the_run_is_over(tmp_path: Path) -> None:
    """The relaxed plans are kept per relaxed model only while the model lives: a run
    that prepared conditions leaves nothing behind once its task is gone (a strong
    reference from the kept plans kept every run's model and grounded task alive). The
    model itself is kept with the domain for the next planning call on it
    (btplan/planner/reuse.py), and goes with it."""
    import gc
    import weakref

    from btplan.acting.departures.prepare import _PLANS

    task = task_of(tmp_path, "blocksworld.bt", DETOUR, "detour")
    index = AchieverIndex(task, OPTIONS)
    relaxed = weakref.ref(index.relaxed)
    outcome = run(task, config=departures(OPTIONS, look_ahead=True, scope_moves=True,
                                          goal_credit=True), models=index)
    assert outcome.reached and relaxed() in _PLANS  # the run kept its relaxed plans
    del outcome, index
    gc.collect()
    assert AchieverIndex(task, OPTIONS).relaxed is relaxed()  # kept for the next call
    del task
    gc.collect()
    assert relaxed() is None
