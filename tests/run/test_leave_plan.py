"""Leaving the offline plan once the world departs from it
(ActingConfig.leave_plan_once_departed, btplan.acting.departures.leave_plan)."""

from __future__ import annotations

from pathlib import Path
from statistics import median

import btplan
from btplan.acting.config import ActingConfig
from btplan.planner.plan_first import UNTIL_DONE, backchained_part
from btplan.bt import Node
from btplan.model import Task
from btplan.sweep.scenarios import resolve
from btplan.worlds.symbolic import SymbolicWorld

ROOT = Path(__file__).resolve().parents[2]


def _disturbed(scenario: str, file: str, seed: int, leave: bool) -> tuple[bool, int, str]:
    """(reached, ticks, the name of the root the run ended on) at p = 0.3."""
    chosen = resolve(scenario)
    task: Task = chosen.prepare(btplan.load(str(ROOT / file)))
    trees: list[Node] = []
    outcome = btplan.run(task, world=SymbolicWorld(task, seed=seed),
                         agents=chosen.agents(task, 0.3, seed), seed=seed, max_ticks=400,
                         config=ActingConfig.default(leave_plan_once_departed=leave),
                         view=lambda root, *rest: trees.append(root))
    return outcome.reached, outcome.ticks, trees[-1].name if trees else ""


def test_under_frequent_disturbances_the_run_leaves_the_plan_and_takes_fewer_ticks() -> None:
    left = [_disturbed("towers", "bench/problems/blocksworld_6.bt", s, True) for s in range(6)]
    kept = [_disturbed("towers", "bench/problems/blocksworld_6.bt", s, False) for s in range(6)]
    assert all(reached for reached, _, _ in left + kept)
    assert median(t for _, t, _ in left) < median(t for _, t, _ in kept) / 2
    assert all(root != UNTIL_DONE for _, _, root in left)
    assert any(root == UNTIL_DONE for _, _, root in kept)


def test_an_undisturbed_run_keeps_the_plan_first() -> None:
    task = btplan.load(str(ROOT / "bench" / "problems" / "blocksworld_6.bt"))
    trees: list[Node] = []
    outcome = btplan.run(task, view=lambda root, *rest: trees.append(root))
    assert outcome.reached
    assert trees[-1].name == UNTIL_DONE
    assert [str(a) for a in outcome.executed] == [str(a) for a in btplan.plan(task).executed]


def test_only_a_plan_first_tree_has_a_backchained_part() -> None:
    task = btplan.load(str(ROOT / "domains" / "pick_place.bt"))
    planned = btplan.plan(task)
    assert backchained_part(planned.tree.root) is None  # four steps, no shorter plan
    shorter = btplan.plan(btplan.load(str(ROOT / "bench" / "problems" / "blocksworld_6.bt")))
    part = backchained_part(shorter.tree.root)
    assert part is not None and part.name != UNTIL_DONE
