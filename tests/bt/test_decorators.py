"""Decorators and Parallel: statuses after every tick and the halts they cause."""

from __future__ import annotations

import pytest
from bt_stubs import ScriptWorld

from btplan.bt import (
    FAILURE,
    RUNNING,
    SUCCESS,
    Action,
    Condition,
    ForceFailure,
    ForceSuccess,
    Inverter,
    Parallel,
    Retry,
    Sequence,
    Timeout,
)


def test_inverter_negates_a_condition_and_passes_running() -> None:
    world = ScriptWorld(scripts={"A": [RUNNING, SUCCESS, FAILURE]})
    assert Inverter(Condition("x")).tick(world) is SUCCESS
    world.facts.add(("x", ()))
    assert Inverter(Condition("x")).tick(world) is FAILURE
    inv = Inverter(Action("A"))
    assert [inv.tick(world) for _ in range(3)] == [RUNNING, FAILURE, SUCCESS]


def test_inverter_child_can_be_replaced_like_any_child() -> None:
    cond = Condition("holding", ("cube",))
    inv = Inverter(cond)
    assert cond.parent is inv
    new = Sequence([Condition("y")])
    inv.replace(cond, new)
    assert inv.child is new and new.parent is inv
    with pytest.raises(ValueError):
        inv.append(Condition("z"))


@pytest.mark.parametrize(("node", "forced"), [(ForceSuccess, SUCCESS), (ForceFailure, FAILURE)])
def test_force_decorators(node: type[ForceSuccess], forced: object) -> None:
    world = ScriptWorld(scripts={"A": [RUNNING, FAILURE, SUCCESS]})
    dec = node(Action("A"))
    assert [dec.tick(world) for _ in range(3)] == [RUNNING, forced, forced]


def test_retry_uses_one_attempt_per_failure_and_reports_running_between() -> None:
    world = ScriptWorld(scripts={"A": [FAILURE, FAILURE, RUNNING, FAILURE, SUCCESS]})
    retry = Retry(Action("A"), attempts=3)
    assert [retry.tick(world) for _ in range(4)] == [RUNNING, RUNNING, RUNNING, FAILURE]
    assert world.take_log() == [("start", "A()"), ("start", "A()"), ("start", "A()"),
                                ("step", "A()")]
    assert retry.tick(world) is SUCCESS, "the count starts again after the last failure"


def test_retry_restarts_within_the_tick_a_child_that_failed_after_running() -> None:
    """BT.CPP 4 does the same; only a child failing at once waits for the next tick."""
    world = ScriptWorld(scripts={"A": [RUNNING, FAILURE, SUCCESS]})
    retry = Retry(Action("A"), attempts=2)
    assert [retry.tick(world), retry.tick(world)] == [RUNNING, SUCCESS]
    assert world.take_log() == [("start", "A()"), ("step", "A()"), ("start", "A()")]


def test_retry_count_resets_on_success_and_on_halt() -> None:
    world = ScriptWorld(scripts={"A": [FAILURE, SUCCESS, FAILURE, FAILURE]})
    retry = Retry(Action("A"), attempts=2)
    assert [retry.tick(world) for _ in range(4)] == [RUNNING, SUCCESS, RUNNING, FAILURE]
    retry.tick(world)
    retry.halt(world)
    assert retry.tick(world) is RUNNING


def test_timeout_halts_a_child_still_running_after_its_ticks() -> None:
    world = ScriptWorld()
    timeout = Timeout(Action("Slow"), ticks=3)
    assert [timeout.tick(world) for _ in range(3)] == [RUNNING, RUNNING, FAILURE]
    assert world.halts == {"Slow()": 1}
    assert timeout.tick(world) is RUNNING, "a fresh count after timing out"
    assert world.take_log()[-1] == ("start", "Slow()")


def test_timeout_passes_a_result_that_comes_in_time() -> None:
    world = ScriptWorld(scripts={"A": [RUNNING, SUCCESS]})
    timeout = Timeout(Action("A"), ticks=2)
    assert [timeout.tick(world), timeout.tick(world)] == [RUNNING, SUCCESS]
    assert world.halts == {}


def test_parallel_succeeds_at_the_threshold_and_halts_the_rest() -> None:
    world = ScriptWorld(scripts={"A": [RUNNING, SUCCESS], "B": [RUNNING, RUNNING, SUCCESS]})
    par = Parallel([Action("A"), Action("B"), Action("C")], success=2)
    assert [par.tick(world) for _ in range(3)] == [RUNNING, RUNNING, SUCCESS]
    assert world.take_log() == [
        ("start", "A()"), ("start", "B()"), ("start", "C()"),
        ("step", "A()"), ("step", "B()"), ("step", "C()"),
        ("step", "B()"), ("halt", "C()"),
    ]


def test_parallel_fails_as_soon_as_success_is_out_of_reach() -> None:
    world = ScriptWorld(scripts={"A": [FAILURE]})
    par = Parallel([Action("A"), Action("B"), Action("C")], success=-1, failure=2)
    assert par.tick(world) is FAILURE
    assert world.take_log() == [("start", "A()")]


def test_parallel_rejects_an_unreachable_threshold() -> None:
    with pytest.raises(ValueError):
        Parallel([Condition("a")], success=2).tick(ScriptWorld())
