"""Sequence and Fallback, reactive and with memory: statuses and halts after every tick."""

from __future__ import annotations

import random

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
    Node,
    Sequence,
    Status,
    World,
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


class _OwnCondition(Condition):
    """A Condition subclass: composites must tick it through its own method."""

    __slots__ = ()
    ticks = 0

    def tick(self, world: World) -> Status:
        _OwnCondition.ticks += 1
        return Condition.tick(self, world)


class _OwnAction(Action):
    """An Action subclass: composites must tick and halt it through its own methods."""

    __slots__ = ()
    calls = 0

    def tick(self, world: World) -> Status:
        _OwnAction.calls += 1
        return Action.tick(self, world)

    def halt(self, world: World) -> None:
        _OwnAction.calls += 1
        Action.halt(self, world)


def _random_tree(rng: random.Random, depth: int, own: bool, names: list[str]) -> Node:
    """A reactive tree of the PA-BT kind with some wider composites; `own` makes its leaves
    subclasses, which the composites do not handle in place."""
    cond, act = (_OwnCondition, _OwnAction) if own else (Condition, Action)
    if depth == 0 or rng.random() < 0.25:
        name = rng.choice(names)
        return cond(name.lower()) if rng.random() < 0.6 else act(name)
    kids = [_random_tree(rng, depth - 1, own, names) for _ in range(rng.randint(1, 4))]
    return (Sequence if rng.random() < 0.5 else Fallback)(kids)


@pytest.mark.parametrize("seed", range(30))
def test_leaves_handled_in_place_tick_and_halt_as_their_own_methods_do(seed: int) -> None:
    names = ["A", "B", "C", "D", "E"]
    trees = [BehaviorTree(_random_tree(random.Random(seed), 5, own, names))
             for own in (False, True)]
    worlds = [ScriptWorld(scripts={n: [RUNNING, RUNNING, SUCCESS, FAILURE, RUNNING]
                                   for n in names[:3]}) for _ in trees]
    flips = random.Random(seed + 1000)
    before = _OwnCondition.ticks, _OwnAction.calls
    for _ in range(25):
        facts = {(n.lower(), ()) for n in names if flips.random() < 0.5}
        statuses = []
        for tree, world in zip(trees, worlds, strict=True):
            world.facts = set(facts)
            statuses.append((tree.tick(world), [n.status for n in tree.nodes()]))
        assert statuses[0] == statuses[1]
        assert worlds[0].take_log() == worlds[1].take_log()
    for tree, world in zip(trees, worlds, strict=True):
        tree.halt(world)
        assert all(n.status is IDLE for n in tree.nodes())
    assert worlds[0].take_log() == worlds[1].take_log()
    assert (_OwnCondition.ticks, _OwnAction.calls) > before
