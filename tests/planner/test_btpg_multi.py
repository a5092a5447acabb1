"""The multi-goal set maker: conjunctions of distinct single goals, each shown solvable."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from types import ModuleType

import pytest

pytest.importorskip("pyperplan")

BENCH = Path(__file__).resolve().parents[2] / "bench"
SINGLE = BENCH / "problems" / "btpg_rw_single"


def _maker() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_btpg_multi", BENCH / "btpg_multi.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_btpg_multi"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_a_small_set_has_the_sizes_asked_and_every_problem_solvable(tmp_path: Path) -> None:
    maker = _maker()
    maker.main([str(SINGLE), str(tmp_path), "--sizes", "2,3", "--count", "2", "--seed", "1"])
    meta = json.loads((tmp_path / "goals.json").read_text(encoding="utf-8"))
    assert meta["difficulty"] == "multi" and meta["seed"] == 1
    assert [r["size"] for r in meta["records"]] == [2, 2, 3, 3]
    domain = (tmp_path / "domain.pddl").read_text(encoding="utf-8")
    assert domain == (SINGLE / "domain.pddl").read_text(encoding="utf-8")
    conjunctions = set()
    for record in meta["records"]:
        assert len(set(record["atoms"])) == record["size"] == len(record["literals"])
        assert len(record["goal"].split(" & ")) == record["size"]
        conjunctions.add(frozenset(record["atoms"]))
        problem = (tmp_path / record["problem"]).read_text(encoding="utf-8")
        steps = maker.pyperplan_plan(domain, problem, 20000, 30.0)
        assert steps is not None
        ok, reason, _ = maker.validate(domain, problem, "\n".join(steps))
        assert ok, reason
    assert len(conjunctions) == 4


def test_goals_that_cannot_hold_together_are_left_out() -> None:
    maker = _maker()
    domain = (SINGLE / "domain.pddl").read_text(encoding="utf-8")
    meta = json.loads((SINGLE / "goals.json").read_text(encoding="utf-8"))
    holding = [g for g in maker.distinct_goals(meta) if g.name.startswith("Holding_")][:2]
    init = maker.initial_state(SINGLE, meta)
    problem = maker.problem_text("btpg-rw", 0, holding, init)
    assert maker.verdict(domain, problem, 300, 30.0) != "solvable"
