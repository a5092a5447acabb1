"""A goal given alone against a task read before (btplan.lang.with_goal)."""

from __future__ import annotations

from pathlib import Path

import pytest

import btplan
from btplan.errors import InputError
from btplan.lang import load_domain, load_problem, with_goal

ROOT = Path(__file__).resolve().parents[2]
RW = ROOT / "bench" / "problems" / "btpg_rw_single"


def test_the_goal_replaces_the_problems_and_the_rest_stays() -> None:
    task = btplan.load(str(ROOT / "domains" / "pick_place.bt"))
    held = with_goal(task, "(and (holding cube) (not (hand_empty)))")
    assert [str(g) for g in held.goal_literals] == ["holding(cube)", "not hand_empty()"]
    assert held.domain is task.domain
    assert held.problem.init == task.problem.init
    assert held.problem.objects == task.problem.objects
    assert [a.name for a in btplan.plan(held).executed] == ["MoveTo", "Pick"]


def test_a_goal_alone_plans_as_its_problem_does() -> None:
    domain = load_domain(str(RW / "domain.pddl"))
    scene = load_problem(domain, str(RW / "p000.pddl"))
    for name in ("p012.pddl", "p004.pddl"):
        read = load_problem(domain, str(RW / name))
        goal = (RW / name).read_text().split("(:goal ", 1)[1].rsplit("(:metric", 1)[0]
        alone = with_goal(scene, goal.strip()[:-1])
        assert alone.goal_literals == read.goal_literals
        assert btplan.plan(alone).executed == btplan.plan(read).executed


@pytest.mark.parametrize(("goal", "message", "column"), [
    ("(holding cub)", "unknown object 'cub' in a goal", 10),
    ("(nosuch cube)", "unknown predicate 'nosuch'", 2),
    ("(holding cube) (free x)", "a goal is one condition", 16),
    ("holding", "expected a condition in parentheses", 1),
    ("", "the goal is empty", 1),
    ("(and (holding cube) (not (holding cube)))", "contradictory goal conditions", 26),
])
def test_a_bad_goal_is_refused_where_it_goes_wrong(goal: str, message: str, column: int) -> None:
    task = btplan.load(str(ROOT / "domains" / "pick_place.bt"))
    with pytest.raises(InputError) as caught:
        with_goal(task, goal, source="--goal")
    assert message in caught.value.message
    if "cub)" in goal:
        assert caught.value.hint == "did you mean 'cube'?"
    assert caught.value.span is not None
    assert (caught.value.span.path, caught.value.span.column) == ("--goal", column)
