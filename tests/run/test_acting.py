"""The run API: outcomes, planner options, and agents written in Python."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from btplan import run
from btplan.acting.config import ActingConfig
from btplan.acting.offline import load
from btplan.errors import InputError
from btplan.model import Atom
from btplan.worlds.agents import Disturbance
from tests.presets import departures

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OBSTACLE = load(str(DOMAINS / "pick_place_obstacle.bt"))
BLOCK_EARLY = ["set:blocks(sphere, tau_goal)@2"]


def test_an_early_obstruction_is_cleared_with_the_published_algorithms() -> None:
    result = run(OBSTACLE, disturb=BLOCK_EARLY, config=ActingConfig.paper())
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


class BlockBehind:
    """Blocks the path to the goal once, when the robot stands there with the cube."""

    name = "block-behind"

    def __init__(self) -> None:
        self.fired = False

    def act(self, world: Any, tick: int) -> list[Disturbance]:
        facts = world.facts()
        if self.fired or not {Atom("holding", ("cube",)), Atom("near", ("goal",))} <= facts:
            return []
        self.fired = True
        world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
        return [Disturbance(tick, self.name, "blocked tau_goal behind the robot", "set")]


@pytest.mark.parametrize("scope", [True, False])
def test_a_path_blocked_behind_the_robot_is_cleared_only_when_scoped(scope: bool) -> None:
    # The early block makes the tree clear the path, a subtree that conflict resolution
    # moves before picking the cube; the second block comes once the robot is at the goal.
    result = run(OBSTACLE, agents=[BlockBehind()], disturb=BLOCK_EARLY, config=departures(look_ahead=True,
                 scope_moves=scope))
    assert result.reached
    total = result.summary()
    assert total.disturbances[-1].agent == "block-behind"
    after = total.started[total.started.index("Place(cube, goal)"):]
    if scope:  # the path is no longer needed: the cube is placed at once
        assert after == ["Place(cube, goal)"] and not total.halted
    else:  # the moved subtree is ticked first and clears the path again
        assert "Place(cube, goal)" in total.halted and "Drop(cube)" in after
