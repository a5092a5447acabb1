"""The replanning baselines: same world and agents as the tree, planner calls counted."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from btplan.acting import load
from btplan.baselines import BaselineOutcome, run_baseline
from btplan.worlds.agents import agents_from_specs
from btplan.worlds.disturb import parse_spec
from btplan.worlds.symbolic import SymbolicWorld

pytest.importorskip("pyperplan")

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
TASK = load(str(DOMAINS / "pick_place.bt"))
PLAN = ["MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]


def act(method: str, *specs: str) -> tuple[BaselineOutcome, SymbolicWorld]:
    world = SymbolicWorld(TASK, seed=0)
    agents = agents_from_specs([parse_spec(s) for s in specs], 0)
    return run_baseline(TASK, world, agents, method, 200), world


@pytest.mark.parametrize("method", ["replan", "repair", "replan-unlimited"])
def test_undisturbed_every_baseline_plans_once(method: str) -> None:
    out, world = act(method)
    assert [str(a) for a in world.executed] == PLAN
    assert (out.reached, out.planner_calls, out.actions) == (True, 1, 4)
    assert out.planning_seconds > 0 and out.checks > 0


def test_an_undone_pick_makes_replan_plan_again() -> None:
    out, world = act("replan", "undo:Pick@5")
    assert out.reached and out.planner_calls == 2
    assert [str(a) for a in world.executed].count("Pick(cube)") == 2


def test_repair_skips_steps_an_agent_did_without_planning() -> None:
    out, world = act("repair", "help:Pick(cube)@2")
    assert out.reached and out.planner_calls == 1
    assert [str(a) for a in world.executed] == [PLAN[0], *PLAN[2:]]


def test_repair_plans_back_to_the_rest_of_its_plan() -> None:
    out, world = act("repair", "undo:MoveTo@4")
    assert out.reached and out.planner_calls == 2
    assert [str(a) for a in world.executed][-2:] == PLAN[-2:]


def test_growing_the_tree_within_a_tick_acts_as_soon_as_a_planner_would() -> None:
    """Algorithm 1 as published spends a tick per expansion; with expansions_per_tick the
    grown tree is ticked again at once, and the undisturbed run is as short as the plan's."""
    from btplan.acting import run
    from btplan.planner import PlannerOptions
    from tests.presets import departures

    paper = run(TASK, max_ticks=50, config=departures(PlannerOptions()))
    eager = run(TASK, max_ticks=50, config=departures(PlannerOptions(expansions_per_tick=16)))
    planned, _ = act("replan")
    assert paper.reached and eager.reached
    assert (paper.ticks, eager.ticks, planned.ticks) == (11, 7, 7)
    assert [str(a) for a in eager.executed] == PLAN
    assert len(eager.summary().expansions) == 4


def test_repair_replans_from_scratch_once_no_way_back_is_found() -> None:
    """A prefix search that finds nothing uses up the tick's call; the next tick must
    replan from scratch rather than search for the same way back again and again."""
    from btplan.acting.strips import Grounding

    class NoWayBack(Grounding):
        def plan(self, state: frozenset[Any], goal: frozenset[str] | None = None) -> Any:
            return None if goal is not None else super().plan(state, goal)

    world = SymbolicWorld(TASK, seed=0)
    agents = agents_from_specs([parse_spec("undo:MoveTo@4")], 0)
    out = run_baseline(TASK, world, agents, "repair", 200, grounding=NoWayBack(TASK))
    assert out.reached and out.planner_calls == 3  # the plan, the way back, a new plan
    assert [str(a) for a in world.executed][-2:] == PLAN[-2:]
