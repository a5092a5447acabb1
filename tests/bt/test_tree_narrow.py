"""BehaviorTree.narrow_to: a subtree becomes the root, its running action goes on."""

from __future__ import annotations

from bt_stubs import ScriptWorld

from btplan.bt import IDLE, RUNNING, Action, BehaviorTree, Parallel, Sequence


def test_the_part_keeps_running_and_the_rest_is_halted() -> None:
    part = Sequence([Action("Go")])
    other = Sequence([Action("Wave")])
    tree = BehaviorTree(Parallel([other, part]))
    world = ScriptWorld()
    assert tree.tick(world) is RUNNING
    world.take_log()
    tree.narrow_to(part, world)
    assert tree.root is part and part.parent is None
    assert world.take_log() == [("halt", "Wave()")]
    assert other.status is IDLE and part.status is RUNNING
    assert tree.tick(world) is RUNNING
    assert world.take_log() == [("step", "Go()")]


def test_narrowing_to_the_root_changes_nothing() -> None:
    root = Sequence([Action("Go")])
    tree = BehaviorTree(root)
    world = ScriptWorld()
    tree.tick(world)
    tree.narrow_to(root, world)
    assert tree.root is root and root.status is RUNNING and world.halts == {}
