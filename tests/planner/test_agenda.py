"""The goal agenda: reasonable orders between goals, decided before the tree is built."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.acting.offline import load, plan
from btplan.model import Atom, GroundLiteral
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.planner.agenda import goal_agenda, reasonable_before
from tests.planner.shapes import DOMAINS
from tests.planner.test_classic import replay, validate


def on(x: str, y: str) -> GroundLiteral:
    return GroundLiteral(Atom("on", (x, y)))


def test_the_lower_block_of_a_tower_goes_first() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))  # goal: on(a, b), on(b, c)
    index = AchieverIndex(task)
    producers, mutexes = index.relaxed.producers, index.mutexes
    # stack(b, c) needs holding(b), which cannot hold while a is on b.
    assert reasonable_before(on("b", "c"), on("a", "b"), producers, mutexes)
    assert not reasonable_before(on("a", "b"), on("b", "c"), producers, mutexes)
    assert goal_agenda([on("a", "b"), on("b", "c")], producers, mutexes) == [
        on("b", "c"), on("a", "b")]
    # Goals with no order between them keep the problem's order.
    assert goal_agenda([on("b", "c"), on("a", "b")], producers, mutexes) == [
        on("b", "c"), on("a", "b")]


def test_a_cycle_is_broken_at_the_goal_listed_first() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    index = AchieverIndex(task)
    # on(a, b) and on(b, a) exclude each other: each is "before" the other.
    goals = [on("a", "b"), on("b", "a")]
    assert goal_agenda(goals, index.relaxed.producers, index.mutexes) == goals


@pytest.mark.parametrize("name", ["planner_sussman", "planner_invert"])
def test_ordered_goals_need_fewer_moves(name: str) -> None:
    task = load(str(DOMAINS / f"{name}.bt"))
    ordered = plan(task, options=PlannerOptions())
    listed = plan(task, options=PlannerOptions(goal_agenda=False))
    for result in (ordered, listed):
        validate(task, result.executed)
        assert replay(task, result) == result.executed
    assert ordered.stats.moves < listed.stats.moves



def test_the_initial_state_orders_a_goal_built_on_a_block_that_must_move(tmp_path: Path) -> None:
    # b sits on a, e on b; the goals put c on b, then a on d. Once c is on b, b cannot
    # be moved, so a cannot be cleared: on(a, d) must come first. The actions alone do
    # not say so.
    from btplan.lang.generators import generate
    from btplan.planner.agenda import state_orders

    domain, _ = generate("blocksworld", "pddl", seed=0, blocks=4)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(
        "(define (problem under) (:domain blocksworld)\n"
        " (:objects a b c d e - block)\n"
        " (:init (on_table a) (on b a) (on e b) (clear e) (on_table c) (clear c)\n"
        "        (on_table d) (clear d) (hand_empty))\n"
        " (:goal (and (on c b) (on a d))))\n")
    task = load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))
    index = AchieverIndex(task)
    producers, mutexes = index.relaxed.producers, index.mutexes
    goals = [on("c", "b"), on("a", "d")]
    assert goal_agenda(goals, producers, mutexes) == goals
    extra = state_orders(goals, mutexes, index.relaxed, task.initial_state)
    assert extra[on("c", "b")] == {on("a", "d")}
    assert not extra.get(on("a", "d"))
    assert goal_agenda(goals, producers, mutexes, extra) == [on("a", "d"), on("c", "b")]
