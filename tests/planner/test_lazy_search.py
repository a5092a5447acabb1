"""The last-resort search as a satisficing planner: packed states, fact landmarks, the
preferred queues and their boost, a search that pauses and goes on, and the early
slice the whole-goal search gets once backchaining's first strategy has failed.

Small generated problems; the counts compared are states expanded, never times.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from types import SimpleNamespace

import pytest

from btplan.acting.offline import load, plan
from btplan.acting.offline import planning as offline
from btplan.acting.offline.whole_goal import SearchTurns
from btplan.errors import NoAchieverError
from btplan.model import GroundLiteral, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.classical.packed import bits
from tests.planner.shapes import DOMAINS, atom, generated
from tests.planner.test_classic import validate

TOGGLE = """
(define (domain toggle)
  (:requirements :strips :negative-preconditions)
  (:predicates (a) (b) (s) (off))
  (:action flip :parameters () :precondition (and (a) (s) (not (off)))
     :effect (and (not (a)) (a) (b))))
"""


def toggle(tmp_path: Path, init: str) -> Task:
    (tmp_path / "domain.pddl").write_text(TOGGLE)
    (tmp_path / "problem.pddl").write_text(
        f"(define (problem t) (:domain toggle) (:init {init}) (:goal (and (a) (b))))")
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))


def blocks(tmp_path: Path, count: int, seed: int) -> Task:
    return generated(tmp_path, "blocksworld", seed, blocks=count)


def test_a_packed_action_deletes_before_it_adds_and_tests_negative_preconditions(
        tmp_path: Path) -> None:
    task = toggle(tmp_path, "(a) (s)")
    engine = AchieverIndex(task).subgoal_search
    packed = engine.packed
    start = packed.encode(task.initial_state)
    assert packed.applicable(start, bits(start)) == [0]
    after = packed.apply(0, start)
    assert after & packed.literal_mask([atom("a()"), atom("b()")]) == packed.literal_mask(
        [atom("a()"), atom("b()")])  # a deleted and added: true, as PDDL has it
    with_off = start | packed.literal_mask([atom("off()")])
    assert packed.applicable(with_off, bits(with_off)) == []
    assert [str(a) for a in engine.search(task.initial_state, task.goal_literals) or []] \
        == ["flip()"]


def test_a_precondition_nothing_changes_holds_only_where_the_start_has_it(
        tmp_path: Path) -> None:
    # s is read by flip and changed by nothing: it gets no bit, and a start without it
    # rules flip out.
    task = toggle(tmp_path, "(a) (s)")
    engine = AchieverIndex(task).subgoal_search
    assert atom("s()") not in engine.packed.ids
    assert engine.search(task.initial_state, task.goal_literals) is not None
    assert engine.search(task.initial_state - {atom("s()")}, task.goal_literals) is None
    assert engine.exhausted


def test_fact_landmarks_are_what_every_relaxed_plan_passes_through() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))  # c on a; a and b on the table
    packed = AchieverIndex(task).subgoal_search.packed
    start = packed.encode(task.initial_state)
    goal = [packed.ids[atom("on(a, b)")]]
    marks = packed.landmarks(bits(start), goal)
    # To stack a on b, a is held, and before that a is cleared: c comes off a.
    for needed in ("on(a, b)", "holding(a)", "clear(a)"):
        assert marks & 1 << packed.ids[atom(needed)], needed
    # b may be held or not: no plan needs it.
    assert not marks & 1 << packed.ids[atom("holding(b)")]


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_boosting_the_preferred_queues_expands_fewer_states(tmp_path: Path, seed: int) -> None:
    task = blocks(tmp_path, 20, seed)
    expanded = []
    for boost in (1000, 0):
        engine = AchieverIndex(task).subgoal_search
        engine.boost = boost
        steps = engine.search(task.initial_state, task.goal_literals, max_states=1000)
        expanded.append(engine.expanded)
        if steps is not None:
            validate(task, steps)
    boosted, even = expanded
    assert boosted < 400
    assert boosted * 2 < even


def test_landmarks_take_part_only_when_the_goal_has_some_beyond_the_start(
        tmp_path: Path) -> None:
    task = blocks(tmp_path, 12, 1)
    engine = AchieverIndex(task).subgoal_search
    run = engine.begin(task.initial_state, task.goal_literals)
    assert run.marks and len(run.queues) == 4
    done = engine.begin(task.initial_state, [GroundLiteral(a) for a in
                                             sorted(task.initial_state)[:1]])
    assert not done.marks and len(done.queues) == 2
    assert done.resume() == []


def test_a_search_paused_at_a_deadline_goes_on_where_it_stopped(tmp_path: Path) -> None:
    task = blocks(tmp_path, 20, 0)
    engine = AchieverIndex(task).subgoal_search
    whole = engine.search(task.initial_state, task.goal_literals)
    run = engine.begin(task.initial_state, task.goal_literals)
    pauses = 0
    while run.resume(deadline=0.0) is None and not run.done:  # a deadline long past
        pauses += 1
        assert run.expanded == 32 * pauses  # the clock is read every 32 states
    assert pauses >= 2
    assert run.plan == whole


def test_the_whole_goal_search_starts_when_the_first_attempt_fails(
        monkeypatch: pytest.MonkeyPatch) -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    attempt = offline.attempt
    tried = []

    def failing(run: object, opts: object, *args: object, **kwargs: object) -> object:
        if kwargs.get("plan") is not None:  # the tree with the searched plan behind it
            return attempt(run, opts, *args, **kwargs)  # type: ignore[arg-type]
        tried.append(opts)
        raise NoAchieverError("stuck")

    monkeypatch.setattr(offline, "attempt", failing)
    result = plan(task, timeout=60)  # with a time limit: its slice comes at once
    assert result.stats.whole_goal and len(tried) == 1
    validate(task, result.executed)
    tried.clear()
    result = plan(task)  # without one: after every strategy (one attempt each), as before
    assert result.stats.whole_goal
    assert len(tried) == len(offline.fallback_strategies(PlannerOptions())) + 1



class _Clock:
    """perf_counter for SearchTurns: time moves only when the search is said to run."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


class _Search:
    """A whole-goal search that uses its whole turn and finds a plan on the `finds`-th."""

    def __init__(self, clock: _Clock, finds: int) -> None:
        self.clock, self.finds = clock, finds
        self.turns: list[tuple[float, float]] = []
        self.proof = None
        self.too_wide = ""
        self.task = SimpleNamespace(goal_literals=[None] * 20)  # twenty goals

    def resume(self, until: float) -> list[str] | None:
        self.turns.append((self.clock.now, until))
        self.clock.now = until
        return ["step"] if len(self.turns) == self.finds else None


def _turns(monkeypatch: pytest.MonkeyPatch, limit: float, until: float,
           finds: int) -> tuple[_Clock, _Search, SearchTurns]:
    """SearchTurns begun at 100 s on a fake clock, with a search that finds on turn `finds`."""
    from btplan.acting.offline import whole_goal

    clock = _Clock()
    monkeypatch.setattr(whole_goal.time, "perf_counter", clock)
    search = _Search(clock, finds)
    turns = whole_goal.SearchTurns(search, 100.0, limit, until)  # type: ignore[arg-type]
    return clock, search, turns


class _Goals:
    """An attempt's count of the goals it holds now, as the test sets it."""

    def __init__(self) -> None:
        self.held = 0

    def __call__(self) -> int:
        return self.held


def test_no_turn_while_backchaining_keeps_reaching_more_goals(
        monkeypatch: pytest.MonkeyPatch) -> None:
    clock, search, turns = _turns(monkeypatch, limit=30.0, until=200.0, finds=1)
    goals = _Goals()
    for second in range(40):  # a goal more every second, far past the first wait (7.5 s)
        clock.now, goals.held = 100.0 + second, second
        assert turns.take(goals) is None
    assert search.turns == []


def test_a_stall_after_the_first_wait_earns_a_turn_as_long_as_the_stall(
        monkeypatch: pytest.MonkeyPatch) -> None:
    clock, search, turns = _turns(monkeypatch, limit=30.0, until=200.0, finds=3)
    goals = _Goals()
    assert turns.take(goals) is None  # the attempt starts, holding no goal
    clock.now, goals.held = 101.0, 2
    assert turns.take(goals) is None  # headway at 101 s
    clock.now = 107.25
    assert turns.take(goals) is None  # stalled 6.25 s, but within a quarter of 30 s
    clock.now = 107.5  # 6.5 s without headway, over a quarter of the 7.5 s run
    assert turns.take(goals) is None and search.turns == [(107.5, 114.0)]
    clock.now = 118.5  # 4.5 s back, within a quarter of 18.5 s: backchaining's
    assert turns.take(goals) is None and len(search.turns) == 1
    clock.now = 119.0  # 5 s: stalled again
    assert turns.take(goals) is None and search.turns[1] == (119.0, 124.0)
    goals.held = 3  # headway: the stall starts over
    assert turns.take(goals) is None
    clock.now = 131.0  # 7 s, within a quarter of 31 s
    assert turns.take(goals) is None and len(search.turns) == 2
    clock.now = 132.0
    assert turns.take(goals) == ["step"] and search.turns[2] == (132.0, 140.0)
    clock.now = 200.0  # backchaining's share is over: the search has the rest anyway
    assert turns.take(goals) is None and len(search.turns) == 3


def test_a_new_attempt_that_only_holds_what_it_started_with_goes_on_stalling(
        monkeypatch: pytest.MonkeyPatch) -> None:
    clock, search, turns = _turns(monkeypatch, limit=30.0, until=200.0, finds=1)
    first, second = _Goals(), _Goals()
    first.held = second.held = 4  # e.g. goals that hold from the start
    assert turns.take(first) is None
    clock.now = 104.0
    assert turns.take(second) is None  # a retry, no further
    clock.now = 108.0
    assert turns.take(second) == ["step"] and search.turns == [(108.0, 116.0)]


def test_the_early_slice_lasts_as_long_as_the_failed_attempt_would_need_at_its_pace(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from btplan.acting.offline.whole_goal import EarlySlice

    clock, search, turns = _turns(monkeypatch, limit=300.0, until=340.0, finds=1)
    goals = _Goals()
    turns.take(goals)  # first looked at, holding none of the 20 goals
    clock.now, goals.held = 102.0, 5
    turns.take(goals)
    clock.now = 102.5  # it fails: 5 goals in 2.5 s, all 20 would take 10 s
    assert EarlySlice(search, 400.0, turns).take() == ["step"]  # type: ignore[arg-type]
    assert search.turns == [(102.5, 112.5)]


def test_an_attempt_that_failed_without_headway_leaves_the_search_half_the_time_left(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from btplan.acting.offline.whole_goal import EarlySlice

    clock, search, turns = _turns(monkeypatch, limit=300.0, until=340.0, finds=1)
    goals = _Goals()
    turns.take(goals)
    clock.now = 101.0
    assert EarlySlice(search, 401.0, turns).take() == ["step"]  # type: ignore[arg-type]
    assert search.turns == [(101.0, 251.0)]


def test_a_plan_found_in_a_search_turn_stops_backchaining_and_is_the_tree(
        monkeypatch: pytest.MonkeyPatch) -> None:
    from btplan.acting.offline import whole_goal

    monkeypatch.setattr(whole_goal, "FIRST_TURN_SHARE", 0.0)  # a turn after the first tick,
    monkeypatch.setattr(whole_goal, "MIN_STALL", 0.0)  # as if backchaining had stalled
    monkeypatch.setattr(whole_goal, "STALL_SHARE", 0.0)
    monkeypatch.setattr(whole_goal, "MIN_TURN", 600.0)  # long enough to find the plan
    task = load(str(DOMAINS / "planner_sussman.bt"))
    result = plan(task, timeout=3600, improve=False)
    assert result.stats.whole_goal
    validate(task, result.executed)
    backchained = plan(task, improve=False)  # no time limit: no turns
    assert not backchained.stats.whole_goal
