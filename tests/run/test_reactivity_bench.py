"""The reactivity report judges btplan against the best baseline at each point."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

from btplan.sweep.runs import Row
from btplan.sweep.stats import summarize

ROOT = Path(__file__).resolve().parents[2]


def bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_reactivity", ROOT / "bench/reactivity.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


R = bench()


def row(method: str, rate: float, seed: int, ticks: int, seconds: float, ok: bool = True,
        setup: float | None = None, cause: str = "") -> Row:
    return {"scenario": "obstacle", "method": method, "rate": rate, "seed": seed, "success": ok,
            "ticks": ticks, "actions": 4, "planner_calls": 1, "planning_seconds": seconds,
            "setup_seconds": setup, "checks": 5.0, "disturbances": 0, "cause": cause,
            "error": ""}


def test_targets_compare_with_the_best_baseline_of_each_measure() -> None:
    rows = [row("btplan", 0.1, s, 12, 0.001, setup=0.002) for s in range(3)]
    rows += [row("replan", 0.1, s, 10, 0.004, setup=0.001) for s in range(3)]
    rows += [row("repair", 0.1, s, 11, 0.010, setup=0.001) for s in range(3)]
    [verdict] = R.verdicts(summarize(rows), rows)
    assert verdict[:3] == ("obstacle", "0.1", "1.00 vs 4.00")
    assert verdict[3] == "4.00x **missed** (target 5x)"  # 5x lower is the target from 0.1
    assert verdict[4:6] == ("3.00 vs 5.00", "1.67x **missed** (target 5x)")  # with set-up
    assert verdict[6].endswith(" met")
    assert verdict[7] == "12 vs 10 **missed**"  # more than 10% above


def test_a_failure_is_explained_by_rerunning_the_seed_with_unlimited_replanning() -> None:
    rows = [row("btplan", 0.0, 0, 400, 0.001, ok=False)]
    assert R.explain_failures(rows) == [("obstacle", "0", "btplan", "1", "0", "1", "0")]


def test_a_failure_with_its_cause_in_the_row_is_not_rerun() -> None:
    rows = [row("btplan", 0.3, 0, 400, 0.001, ok=False, cause="no way in budget"),
            row("repair", 0.3, 0, 400, 0.001, ok=False, cause="own")]
    assert R.explain_failures(rows) == [("obstacle", "0.3", "btplan", "1", "1", "0", "0"),
                                        ("obstacle", "0.3", "repair", "1", "0", "1", "0")]
