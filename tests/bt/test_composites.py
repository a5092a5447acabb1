"""Sequence and Fallback, reactive and with memory: statuses and halts after every tick."""

from __future__ import annotations

import pytest
from bt_stubs import ScriptWorld

from btplan.bt import (
    FAILURE,
    IDLE,
    RUNNING,
    SUCCESS,
    Action,
    BehaviorTree,
    Condition,
    Fallback,
    Sequence,
)


def test_reactive_sequence_rechecks_the_condition_and_halts_the_running_action() -> None:
    seq = Sequence([Condition("ready"), Action("Go")])
    world = ScriptWorld(facts={("ready", ())})
    tree = BehaviorTree(seq)
    assert tree.tick(world) is RUNNING
    assert world.take_log() == [("start", "Go()")]
    assert tree.tick(world) is RUNNING
    assert world.take_log() == [("step", "Go()")]
    world.facts.clear()
    assert tree.tick(world) is FAILURE
    assert world.take_log() == [("halt", "Go()")]
    assert seq.children[1].status is IDLE
    world.facts.add(("ready", ()))
    assert tree.tick(world) is RUNNING
    assert world.take_log() == [("start", "Go()")], "a halted action starts afresh"


def test_memory_sequence_resumes_the_running_child_without_rechecking() -> None:
    seq = Sequence([Condition("ready"), Action("Go")], memory=True)
    world = ScriptWorld(facts={("ready", ())}, scripts={"Go": [RUNNING, RUNNING, SUCCESS]})
    assert seq.tick(world) is RUNNING
    world.facts.clear()
    assert seq.tick(world) is RUNNING, "the condition is not ticked again"
    assert seq.tick(world) is SUCCESS
    assert world.take_log() == [("start", "Go()"), ("step", "Go()"), ("step", "Go()")]
    assert seq.tick(world) is FAILURE, "after finishing it starts at the first child"


def test_memory_sequence_restarts_after_failure() -> None:
    seq = Sequence([Action("A"), Action("B")], memory=True)
    world = ScriptWorld(scripts={"A": [SUCCESS], "B": [RUNNING, FAILURE, SUCCESS]})
    assert [seq.tick(world) for _ in range(3)] == [RUNNING, FAILURE, SUCCESS]
    assert world.take_log() == [("start", "A()"), ("start", "B()"), ("step", "B()"),
                                ("start", "A()"), ("start", "B()")]


def test_reactive_fallback_halts_a_lower_priority_action_when_a_higher_one_succeeds() -> None:
    fb = Fallback([Condition("done"), Action("Work")])
    world = ScriptWorld()
    assert fb.tick(world) is RUNNING
    world.facts.add(("done", ()))
    assert fb.tick(world) is SUCCESS
    assert world.halts == {"Work()": 1}
    assert fb.tick(world) is SUCCESS
    assert world.halts == {"Work()": 1}, "an idle action is not halted twice"


def test_fallback_tries_the_next_action_when_one_fails() -> None:
    fb = Fallback([Action("A"), Action("B")])
    world = ScriptWorld(scripts={"A": [FAILURE], "B": [RUNNING, SUCCESS]})
    assert fb.tick(world) is RUNNING
    assert fb.tick(world) is SUCCESS
    assert world.take_log() == [("start", "A()"), ("start", "B()"),
                                ("start", "A()"), ("step", "B()")]


def test_memory_fallback_resumes_the_running_child() -> None:
    fb = Fallback([Action("A"), Action("B")], memory=True)
    world = ScriptWorld(scripts={"A": [FAILURE], "B": [RUNNING, SUCCESS]})
    assert [fb.tick(world) for _ in range(2)] == [RUNNING, SUCCESS]
    assert world.take_log() == [("start", "A()"), ("start", "B()"), ("step", "B()")]


def test_a_running_action_earlier_in_a_sequence_halts_a_later_one() -> None:
    first, second = Action("First"), Action("Second")
    seq = Sequence([Fallback([Condition("ok"), first]), second])
    world = ScriptWorld(facts={("ok", ())})
    assert seq.tick(world) is RUNNING  # Second runs
    world.facts.clear()
    assert seq.tick(world) is RUNNING  # First now runs, Second is no longer reached
    assert world.take_log() == [("start", "Second()"), ("start", "First()"), ("halt", "Second()")]
    assert (first.status, second.status) == (RUNNING, IDLE)


def test_halting_the_tree_halts_every_running_action_once() -> None:
    par_a, par_b = Action("A"), Action("B")
    tree = BehaviorTree(Sequence([Fallback([Condition("x"), par_a]), Fallback([par_b])]))
    world = ScriptWorld()
    tree.tick(world)
    tree.halt(world)
    assert world.halts == {"A()": 1}
    assert all(n.status is IDLE for n in tree.nodes())


def test_empty_composites_follow_their_identity_element() -> None:
    world = ScriptWorld()
    assert Sequence([]).tick(world) is SUCCESS
    assert Fallback([]).tick(world) is FAILURE


def test_structure_edits_keep_parent_links() -> None:
    a, b, c = Condition("a"), Condition("b"), Condition("c")
    seq = Sequence([a, b])
    seq.replace(a, c)
    assert seq.children == [c, b] and c.parent is seq and a.parent is None
    assert seq.remove(b) == 1 and b.parent is None
    seq.insert(0, b)
    assert seq.index_of(c) == 1
    with pytest.raises(ValueError):
        Sequence([c])
