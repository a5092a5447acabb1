"""The debug check: a condition never answers RUNNING, an action always answers a status."""

from __future__ import annotations

import pytest
from bt_stubs import ScriptWorld

from btplan.bt import (
    RUNNING,
    SUCCESS,
    Action,
    BehaviorTree,
    Condition,
    LeafContractError,
    Sequence,
    Status,
)
from btplan.bt.world import LeafKey


class RunningConditions(ScriptWorld):
    def check(self, key: LeafKey) -> bool:
        return RUNNING  # type: ignore[return-value]


class NoneActions(ScriptWorld):
    def start(self, key: LeafKey) -> Status:
        return None  # type: ignore[return-value]


def test_debug_tree_rejects_a_condition_answering_running() -> None:
    tree = BehaviorTree(Sequence([Condition("holding", ("cube",))]), debug=True)
    with pytest.raises(LeafContractError, match=r"holding\(cube\).*never RUNNING"):
        tree.tick(RunningConditions())


def test_debug_tree_rejects_an_action_answering_none() -> None:
    tree = BehaviorTree(Action("Pick", ("cube",)), debug=True)
    with pytest.raises(LeafContractError, match=r"Pick\(cube\): start returned None"):
        tree.tick(NoneActions())


def test_without_debug_the_same_mistake_goes_unnoticed() -> None:
    """Why the check exists: a truthy RUNNING reads as SUCCESS."""
    tree = BehaviorTree(Condition("holding", ("cube",)))
    assert tree.tick(RunningConditions()) is SUCCESS


def test_debug_tree_ticks_a_correct_world_normally() -> None:
    tree = BehaviorTree(Sequence([Condition("a"), Action("B")]), debug=True)
    assert tree.tick(ScriptWorld(facts={("a", ())}, scripts={"B": [SUCCESS]})) is SUCCESS
