"""The tick benchmark compares like with like: every engine reaches the same nodes, halts the
same actions and answers the same status, tick by tick, on trees whose facts flip."""

from __future__ import annotations

import importlib.util
import random
import sys
from pathlib import Path
from types import ModuleType

import pytest

pytest.importorskip("py_trees")
pytest.importorskip("behaviortreepy")
BENCH = Path(__file__).resolve().parents[2] / "bench" / "ticks.py"


def bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_ticks", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_ticks"] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize(("nodes", "seed"), [(300, 1), (1000, 3)])
def test_every_engine_reaches_and_halts_the_same_nodes(nodes: int, seed: int) -> None:
    ticks = bench()
    shape = ticks.goal_forest(nodes, seed)
    assert ticks.size(shape) >= nodes
    plan = ticks.scenario(shape, random.Random(seed))
    found = ticks.engines(shape, plan)  # raises unless their counted ticks agree
    assert [e.name for e in found] == ["btplan", "BT.CPP Python leaves", "BT.CPP C++ leaves",
                                       "py_trees"]
    traces = [[(n, s) for n, _, s in e.trace] for e in found]
    assert all(t == traces[0] for t in traces)
    assert all(s == "RUNNING" for _, s in traces[0])
    assert found[0].trace[-2:] == found[1].trace[-2:] == found[3].trace[-2:]
    assert sum(h for _, h, _ in found[0].trace[-2:]) > 0, "flipping facts halt actions"
    assert 10 < found[0].per_period() < 2 * ticks.size(shape)


def test_a_disagreement_is_caught() -> None:
    ticks = bench()
    shape = ticks.goal_forest(300, 1)
    plan = ticks.scenario(shape, random.Random(1))
    ours = ticks.btplan_engine(shape, plan)
    skewed = ticks.Engine("other", ours.period, [(n + 1, h, s) for n, h, s in ours.trace])
    with pytest.raises(AssertionError, match="tick 1: btplan reached"):
        ticks.check_agreement([ours, skewed])


def test_a_short_run_of_the_btcpp_comparison_prints_the_table_and_the_target() -> None:
    ticks = bench()
    row = ticks.measure(300, 1, seconds=0.06, rounds=1, with_py_trees=False)
    assert row.halts > 0 and row.reached > 10
    assert set(row.rates) == {"btplan", "BT.CPP Python leaves", "BT.CPP C++ leaves"}
    assert all(rate > 0 for rate in row.rates.values())
    lines = ticks.table([row]) + ticks.verdicts([row])
    assert lines[1].split()[:6] == ["nodes", "reached", "halts", "btplan", "BT.CPP", "py"]
    assert lines[2].split()[0] == str(ticks.size(ticks.goal_forest(300, 1)))
    assert lines[-1].startswith(ticks.TARGET + " (worst ratio ")
    assert lines[-1].endswith((": met", ": missed"))
