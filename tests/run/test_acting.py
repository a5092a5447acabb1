"""The run API: outcomes, planner options, and agents written in Python."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from btplan import run
from btplan.acting.offline import load
from btplan.errors import InputError
from btplan.model import Atom
from btplan.planner import PlannerOptions
from btplan.worlds.agents import Disturbance

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OBSTACLE = load(str(DOMAINS / "pick_place_obstacle.bt"))
BLOCK_EARLY = ["set:blocks(sphere, tau_goal)@2"]


def test_an_early_obstruction_is_cleared_with_the_published_algorithms() -> None:
    result = run(OBSTACLE, disturb=BLOCK_EARLY, options=PlannerOptions.paper())
    assert result.reached
    finished = result.summary().finished
    assert finished.index("Pick(sphere)") < finished.index("Place(sphere, aside)")
    assert finished.index("Place(sphere, aside)") < finished.index("Place(cube, goal)")


def test_a_run_that_cannot_go_on_ends_not_reached_with_the_reason() -> None:
    task = load(str(DOMAINS / "pick_place.bt"))
    result = run(task, disturb=["clear:free(tau_cube)@1"])
    assert not result.reached
    assert "no action can make" in result.reason
    assert result.ticks == len(result.records) >= 1


class Saboteur:
    """Blocks the path once, as soon as the robot holds the cube."""

    name = "saboteur"

    def __init__(self) -> None:
        self.fired = False

    def act(self, world: Any, tick: int) -> list[Disturbance]:
        if self.fired or Atom("holding", ("cube",)) not in world.facts():
            return []
        self.fired = True
        world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
        return [Disturbance(tick, self.name, "blocked tau_goal", "set")]


def test_python_agents_act_beside_spec_agents() -> None:
    result = run(OBSTACLE, agents=[Saboteur()], disturb=["undo:Pick@30.."])
    assert result.reached
    total = result.summary()
    assert total.disturbances[0].agent == "saboteur"
    assert "not blocks(_, tau_goal)" in [e.condition for _, e in total.expansions]


def test_bad_specs_raise_located_input_errors() -> None:
    with pytest.raises(InputError) as caught:
        run(OBSTACLE, disturb=["set:blocks(sphere)@2"])
    assert "blocks takes 2 arguments, not 1" in str(caught.value)
