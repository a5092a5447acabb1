"""The tick benchmark compares like with like: both engines reach the same nodes per tick."""

from __future__ import annotations

import importlib.util
import random
import sys
from pathlib import Path
from types import ModuleType

import pytest

from btplan.bt import BehaviorTree
from btplan.bt.trace import TickRecorder

pytest.importorskip("py_trees")
BENCH = Path(__file__).resolve().parents[2] / "bench" / "ticks.py"


def bench() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_ticks", BENCH)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["bench_ticks"] = module
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("nodes", [300, 1000])
def test_both_engines_reach_the_same_nodes_and_stay_running(nodes: int) -> None:
    ticks = bench()
    shape = ticks.goal_forest(nodes, seed=3)
    assert ticks.size(shape) >= nodes
    true, running = ticks.facts(shape, random.Random(3))
    _ours, n_ours, s_ours = ticks.btplan_engine(shape, true, running)
    _theirs, n_theirs, s_theirs = ticks.py_trees_engine(shape, true, running)
    assert (n_ours, s_ours) == (n_theirs, s_theirs) == (n_ours, "RUNNING")
    assert 10 < n_ours < ticks.size(shape)
    tree = BehaviorTree(ticks.build_btplan(shape))
    recorder = TickRecorder()
    recorder.attach(tree)
    world = ticks.SetWorld({(c, ()) for c in true}, {(a, ()) for a in running})
    for _ in range(3):
        tree.tick(world)
    assert [len(t.nodes) for t in recorder.traces] == [n_ours] * 3, "same work every tick"
