"""The default run plans offline before its first action (ActingConfig.plan_before_acting):
undisturbed, it executes what `btplan plan` plans, and halts nothing."""

from __future__ import annotations

from itertools import count
from pathlib import Path

import pytest

import btplan
from btplan.acting.config import ActingConfig
from btplan.lang.generators import assembly, blocksworld, logistics
from btplan.model import Task
from btplan.robot import Robot
from btplan.worlds.symbolic import SymbolicWorld

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
SHIPPED = ["blocksworld.bt:sussman", "gripper.bt", "logistics.bt", "planner_swap.bt",
           "planner_sussman.bt", "fetch_cup.bt"]


def shipped(label: str) -> Task:
    name, _, problem = label.partition(":")
    return btplan.load(str(DOMAINS / name), problem=problem or None)


def task(made: tuple[object, object]) -> Task:
    domain, problem = made
    return Task(domain=domain, problem=problem)


GENERATED = {
    "blocksworld 6 s1": lambda: task(blocksworld(6, seed=1)),
    "logistics 3 s2": lambda: task(logistics(3, seed=2)),
    "assembly 6 s2": lambda: task(assembly(6, seed=2)),
}


@pytest.mark.parametrize("label", SHIPPED + sorted(GENERATED))
def test_an_undisturbed_default_run_executes_no_more_than_the_plan(label: str) -> None:
    made = GENERATED[label]() if label in GENERATED else shipped(label)
    planned = btplan.plan(made)
    outcome = btplan.run(made)
    assert outcome.reached, outcome.reason
    assert len(outcome.executed) <= len(planned.executed)
    assert outcome.summary().count("halted") == 0


def test_without_planning_ahead_the_loop_executes_more_on_the_same_problem() -> None:
    """What the option buys: the loop alone takes the long way round gripper.bt."""
    task = shipped("gripper.bt")
    alone = btplan.run(task, config=ActingConfig.default(plan_before_acting=False))
    assert len(alone.executed) > len(btplan.run(task).executed)


def test_the_first_tick_reports_the_offline_expansions() -> None:
    outcome = btplan.run(shipped("gripper.bt"))
    assert outcome.reached
    assert outcome.records[0].expansions and outcome.records[0].planning_seconds > 0


def test_a_stop_request_while_planning_ahead_ends_the_run_before_any_action() -> None:
    made = GENERATED["blocksworld 6 s1"]()
    asked = count()
    # Asked once before the first tick; the planning asks after each of its own ticks.
    outcome = btplan.run(made, world=SymbolicWorld(made), stop=lambda: next(asked) >= 2)
    assert outcome.interrupted and not outcome.reached
    assert outcome.executed == [] and outcome.summary().count("started") == 0


def test_a_robot_with_refiners_of_its_own_declares_values_planning_cannot_know() -> None:
    """Such a robot is not planned ahead (tests/robot/test_robot_api.py runs one: its
    refiner is asked for every MoveTo)."""
    robot = Robot()
    assert not robot.capabilities.own_values

    @robot.refiner("MoveTo", "t")
    def trajectory(ask: object) -> list[str]:
        return []

    assert robot.capabilities.own_values
