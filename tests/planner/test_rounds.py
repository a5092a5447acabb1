"""Offline planning's rounds: a run whose expansions all came before its first action is
already a run of the final tree from the initial state, and needs no second round."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import btplan
from btplan.acting.offline import plan
from btplan.acting.offline.improved import run_from_start
from btplan.lang import load_domain, load_problem, with_goal
from btplan.planner import PlannerOptions

ROOT = Path(__file__).resolve().parents[2]
RW = ROOT / "bench" / "problems" / "btpg_rw_single"


def rw_goals(count: int) -> list[str]:
    records = json.loads((RW / "goals.json").read_text())["records"]
    return [f"(and {' '.join(r['atoms'])})" for r in records[:count]]


@pytest.mark.parametrize("goal", rw_goals(12))
def test_one_round_when_every_expansion_came_before_the_first_action(goal: str) -> None:
    scene = load_problem(load_domain(str(RW / "domain.pddl")), str(RW / "p000.pddl"))
    task = with_goal(scene, goal)
    result = plan(task, improve=False)
    assert result.stats.rounds == 1
    # the tree does from the start what the round did
    again = run_from_start(result.tree, task, 0, result.executed)
    assert again is not None and again[0] == result.executed


def test_a_round_that_acted_before_expanding_again_is_checked_by_another() -> None:
    # Breadth-first expansion on Example 2: the robot moves before the path is found blocked
    task = btplan.load(str(ROOT / "domains" / "pick_place_obstacle.bt"))
    result = plan(task, options=PlannerOptions(closest_first=False), improve=False)
    assert result.stats.rounds >= 2
    assert run_from_start(result.tree, task, 0, result.executed) is not None
