"""The reactivity benchmark compares like with like: a correct baseline, the same streams."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

from btplan.acting.offline import load

ROOT = Path(__file__).resolve().parents[2]


def bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_reactivity", ROOT / "bench/reactivity.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


R = bench()
TASK = load(str(ROOT / "domains/pick_place.bt"))


def test_the_baseline_plans_the_shortest_sequence() -> None:
    plan = R.bfs_plan(TASK, TASK.initial_state)
    assert [str(a) for a in plan] == ["MoveTo(cube, tau_cube)", "Pick(cube)",
                                      "MoveTo(goal, tau_goal)", "Place(cube, goal)"]


def test_undisturbed_the_tree_pays_one_tick_per_expansion() -> None:
    """Both chain finished actions into the next one within a tick; the tree also spends
    the ticks in which it fails and grows (Algorithm 1 ticks until FAILURE, then expands)."""
    calm = R.replanning_episode(TASK, [], 0, 100)
    blended = R.blended_episode(TASK, [], 0, 100)
    assert calm.reached and blended.reached
    assert (calm.planner_calls, blended.planner_calls) == (1, 4)
    assert calm.ticks == 7
    assert blended.ticks == calm.ticks + blended.planner_calls


def test_the_baseline_replans_when_the_next_step_cannot_run() -> None:
    scenario = R.SCENARIOS[0]
    agents = R.make_agents(scenario, ["undo:Pick@5"], 0.0, 0)
    episode = R.replanning_episode(TASK, agents, 0, 100)
    assert episode.reached
    assert episode.planner_calls == 2
    assert episode.disturbances == 1


def test_a_seed_fixes_the_stream_and_both_executors_finish_under_it() -> None:
    scenario = R.SCENARIOS[0]
    streams = ["fail:MoveTo@p=0.3"]

    def fired(seed: int) -> list[int]:
        agents = R.make_agents(scenario, streams, 0.3, seed)
        return [t for t in range(1, 60) if agents[0].fires(t)]

    assert fired(7) == fired(7)
    blended = R.blended_episode(TASK, R.make_agents(scenario, streams, 0.3, 7), 7, 200)
    replanned = R.replanning_episode(TASK, R.make_agents(scenario, streams, 0.3, 7), 7, 200)
    assert blended.reached and replanned.reached


def test_pyperplan_as_replanner_finds_a_plan_of_the_same_length() -> None:
    task = load(str(ROOT / "domains/pick_place_obstacle.bt"))
    state = task.initial_state
    assert len(R.pyperplan_plan(task, state)) == len(R.bfs_plan(task, state)) == 4
    episode = R.replanning_episode(task, [], 0, 100, planner=R.pyperplan_plan)
    assert episode.reached and episode.planner_calls == 1
