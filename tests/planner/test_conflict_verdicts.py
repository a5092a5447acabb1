"""Asking whether a subtree conflicts gives the verdict of listing its conflicts.

`has_conflicts` and `Judge.blocked` answer yes or no without spelling conflicts out
(and read an earlier sibling's actions only when the mutexes leave a need uncovered);
conflict resolution asks them where only the verdict matters. Checked on every atomic
BT of the trees the blended loop grows in disturbed runs.
"""

from __future__ import annotations

from typing import Any

import pytest

import btplan.acting.loop as loop_module
from btplan.bt import Fallback
from btplan.planner.conflicts import (
    Judge,
    achiever_leaves,
    find_conflicts,
    guarantees,
    has_conflicts,
    needs_by_alternative,
    sequence_slots,
)
from btplan.sweep.runs import Job, run_one

SCENARIOS = {
    "towers": ("bench/problems/blocksworld_6.bt",),
    "packages": ("bench/problems/logistics_1.bt",),
}


def test_the_verdicts_agree_with_the_listed_conflicts(monkeypatch: pytest.MonkeyPatch) -> None:
    real = loop_module.resolve_conflicts
    seen = {"conflicts": 0, "none": 0, "blocked": 0, "free": 0}

    def checking(tree: Any, subtree: Any, judge: Judge, *args: Any) -> Any:
        for node in tree.root.walk():
            if not isinstance(node, Fallback) or node.parent is None:
                continue
            listed = find_conflicts(node, judge)
            assert has_conflicts(node, judge) == bool(listed)
            seen["conflicts" if listed else "none"] += 1
            ways = needs_by_alternative(node, judge.guards)
            for sequence, index in sequence_slots(node):
                for earlier in sequence.children[:index]:
                    held = guarantees(earlier)
                    blocks = judge.blocks(held, node, achiever_leaves(earlier), "", ways)
                    assert judge.blocked(held, ways, earlier) == bool(blocks)
                    seen["blocked" if blocks else "free"] += 1
        return real(tree, subtree, judge, *args)

    monkeypatch.setattr(loop_module, "resolve_conflicts", checking)
    for scenario, files in SCENARIOS.items():
        for seed in range(3):
            row = run_one(Job(files, scenario), "btplan", 0.2, seed)
            assert row["error"] == "" and row["success"], row
    assert all(seen.values()), seen  # packages' trucks block: each kind of verdict met
