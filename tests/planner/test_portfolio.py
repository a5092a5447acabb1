"""The whole-goal search's second configuration: actions that make a landmark still
to reach true are preferred, and two searches take turns (`search.Portfolio`).

Small problems; the counts compared are states expanded, never times.
"""

from __future__ import annotations

from pathlib import Path

from btplan.acting.offline import load
from btplan.model import Task
from btplan.planner import AchieverIndex
from btplan.classical.search import SLICE, Portfolio
from tests.planner.shapes import generated
from tests.planner.test_classic import validate
from tests.planner.test_lazy_search import toggle

# l is a landmark of g with two achievers; the relaxed plan takes the first one.
TWO_WAYS = """
(define (domain two-ways)
  (:requirements :strips)
  (:predicates (l) (z) (g))
  (:action first :parameters () :precondition (and) :effect (l))
  (:action second :parameters () :precondition (and) :effect (and (l) (z)))
  (:action finish :parameters () :precondition (l) :effect (g)))
"""


def two_ways(tmp_path: Path) -> Task:
    (tmp_path / "domain.pddl").write_text(TWO_WAYS)
    (tmp_path / "problem.pddl").write_text(
        "(define (problem p) (:domain two-ways) (:init) (:goal (g)))")
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))


def preferred_children(task: Task, landmark_preferred: bool) -> set[str]:
    """The actions whose children wait in the h_FF preferred queue after one expansion."""
    engine = AchieverIndex(task).subgoal_search
    engine.landmark_preferred = landmark_preferred
    run = engine.begin(task.initial_state, task.goal_literals)
    assert run.resume(states=1) is None and run.expanded == 1
    return {engine.actions[entry % run.width - 1].name for entry in run.queues[1].entries()}


def test_actions_reaching_a_landmark_are_preferred_beside_the_relaxed_plan(
        tmp_path: Path) -> None:
    task = two_ways(tmp_path)
    assert preferred_children(task, landmark_preferred=False) == {"first"}
    assert preferred_children(task, landmark_preferred=True) == {"first", "second"}


def test_the_future_landmarks_are_those_the_count_counts(tmp_path: Path) -> None:
    task = generated(tmp_path, "blocksworld", 1, blocks=8)
    engine = AchieverIndex(task).subgoal_search
    run = engine.begin(task.initial_state, task.goal_literals)
    start = run.engine.packed.encode(task.initial_state)
    passed = run.progress(run.before_start, start)
    future = run.future(start, passed)
    assert future and future == run.marks  # nothing reached yet
    assert bin(future).count("1") == run.count(start, passed)


def test_a_search_stops_after_the_states_asked_for_and_goes_on(tmp_path: Path) -> None:
    task = generated(tmp_path, "blocksworld", 0, blocks=12)
    engine = AchieverIndex(task).subgoal_search
    whole = engine.search(task.initial_state, task.goal_literals)
    run = engine.begin(task.initial_state, task.goal_literals)
    assert run.resume(states=5) is None and run.expanded == 5
    assert run.resume() == whole


def _portfolio(tmp_path: Path) -> tuple[Task, Portfolio]:
    """A 20-block problem's whole-goal search, both searches begun, none expanded."""
    task = generated(tmp_path, "blocksworld", 2, blocks=20)
    engine = AchieverIndex(task).subgoal_search
    portfolio = engine.begin(task.initial_state, task.goal_literals, portfolio=True)
    assert isinstance(portfolio, Portfolio)
    return task, portfolio


def test_a_portfolio_takes_turns_and_returns_the_first_plan_found(tmp_path: Path) -> None:
    task, portfolio = _portfolio(tmp_path)
    first, second = portfolio.runs
    assert not first.landmark_preferred and second.landmark_preferred
    steps = portfolio.resume()
    assert steps is not None and portfolio.done
    validate(task, steps)
    assert portfolio.expanded == first.expanded + second.expanded


def test_the_turn_goes_to_the_search_that_improved_last(tmp_path: Path) -> None:
    task, portfolio = _portfolio(tmp_path)
    first, second = portfolio.runs
    portfolio.resume(deadline=0.0)  # a deadline long past: one turn, cut at 32 states
    assert (first.expanded, second.expanded) == (32, 0)  # ties go to the first
    first.better_at = first.expanded - SLICE  # as if the first had stalled for a while
    portfolio.resume(deadline=0.0)
    assert (first.expanded, second.expanded) == (32, 32)


def test_a_portfolio_stops_when_one_search_shows_there_is_no_plan(tmp_path: Path) -> None:
    task = toggle(tmp_path, "(a)")  # flip needs s, which nothing makes true
    engine = AchieverIndex(task).subgoal_search
    portfolio = engine.begin(task.initial_state, task.goal_literals, portfolio=True)
    assert portfolio.resume() is None
    assert portfolio.done and portfolio.exhausted
