"""The baselines in a world that refines values the task does not declare (the simulator)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.acting import load
from btplan.acting.refined import RefinedGrounding, asks_world
from btplan.cli import app
from btplan.model import ActionTemplate, Atom, Parameter
from btplan.sweep import Job
from btplan.sweep.output import read_rows
from btplan.sweep.runs import run_one

pytest.importorskip("pyperplan")

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
YOUBOT = str(DOMAINS / "youbot.bt")
TASK = load(YOUBOT)
runner = CliRunner()


class Refiner:
    """A world that names a path per location and an aside spot per cube, and whose
    path to the goal is blocked by blue."""

    def __init__(self, facts: set[Atom]) -> None:
        self.facts_now = facts
        self.asked: list[tuple[str, dict[str, str]]] = []
        self.checked: list[tuple[str, tuple[str, ...]]] = []

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        self.asked.append((template.name, dict(binding)))
        if parameter.type == "trajectory":
            return [f"to_{binding['l']}"]
        return [f"aside_{binding['c']}"]

    def check(self, key: tuple[str, tuple[str, ...]]) -> bool:
        self.checked.append(key)
        return False

    def facts(self) -> frozenset[Atom]:
        return frozenset(self.facts_now)


def test_the_simulator_task_needs_the_world_and_example_2_does_not() -> None:
    assert asks_world(TASK)
    assert not asks_world(load(str(DOMAINS / "pick_place_obstacle.bt")))


def test_grounding_asks_the_world_until_no_new_value_and_plans_around_an_obstacle() -> None:
    world = Refiner({Atom("hand_empty", ()), Atom("blocks", ("blue", "to_goal"))})
    grounding = RefinedGrounding(TASK, world)
    state = grounding.observe(world)
    plan = [str(a) for a in grounding.plan(state) or []]
    # Paths to the aside spots are asked for in a second round, once the spots exist.
    assert ("MoveTo", {"l": "aside_blue"}) in world.asked
    assert plan[:4] == ["MoveTo(blue, to_blue)", "Pick(blue)",
                        "MoveTo(aside_blue, to_aside_blue)", "Place(blue, aside_blue)"]
    assert plan[-1] == "Place(green, goal)"  # the goal names where green goes
    grounded = {str(a) for a in grounding.ground(state).actions}
    assert "Place(blue, goal)" not in grounded  # ...and where green goes, not blue
    assert not world.checked  # no path known yet
    grounding.observe(world)
    assert ("blocks", ("_", "to_goal")) in world.checked  # measured anew, as the tree does
    first = grounding.current
    grounding.plan(state)
    assert grounding.current is first  # the world gave nothing new: no grounding anew
    assert "aside_blue" in grounding.task.object_types  # the values are objects


def test_a_path_to_an_aside_spot_counts_as_free_until_a_move_along_it_failed() -> None:
    world = Refiner({Atom("hand_empty", ()), Atom("blocks", ("blue", "to_goal"))})
    grounding = RefinedGrounding(TASK, world)
    plan = grounding.plan(grounding.observe(world)) or []
    blue, red = Atom("blocks", ("blue", "to_aside_blue")), Atom("blocks", ("red", "to_aside_blue"))
    world.facts_now |= {blue, red}
    world.checked.clear()
    seen = grounding.observe(world)
    assert blue not in seen and red not in seen  # measured from here, driven from elsewhere
    assert ("blocks", ("_", "to_aside_blue")) not in world.checked
    grounding.failed(next(a for a in plan if a.args == ("aside_blue", "to_aside_blue")))
    seen = grounding.observe(world)
    assert red in seen  # another cube does block it
    assert blue not in seen  # blue is carried along it
    assert ("blocks", ("_", "to_aside_blue")) in world.checked


@pytest.mark.slow
def test_replan_and_repair_reach_the_goal_in_the_simulator(tmp_path: Path) -> None:
    pytest.importorskip("pybullet")
    out = tmp_path / "rows.csv"
    # Seed 2: on seeds 0, 1 and 3 plan repair drops green in the doorway, where the agent
    # that takes yellow away pushes it out of the scene or under the robot's base, or
    # finds no plan (docs/results/reactivity.md, the baselines' failures on `shove`); which seeds
    # do depends on the physics.
    result = runner.invoke(app, ["sweep", YOUBOT, "--sim", "pybullet", "--scenario", "scene",
                                 "--seeds", "2:3", "--rates", "0", "--method", "replan,repair",
                                 "-j", "1", "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    rows = {r["method"]: r for r in read_rows(str(out))}
    assert sorted(rows) == ["repair", "replan"]
    for row in rows.values():
        assert row["success"] and not row["error"], row
        assert row["planner_calls"] >= 1 and row["planning_seconds"] > 0
        assert row["actions"] >= 4  # to the cube, pick, to the goal, place


@pytest.mark.slow
def test_a_failure_inside_a_simulator_baseline_is_an_error_row(
        monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("pybullet")

    def broken(self: RefinedGrounding, state: frozenset[Atom],
               goal: frozenset[str] | None = None) -> None:
        raise RuntimeError("the planner broke")

    monkeypatch.setattr(RefinedGrounding, "plan", broken)
    row = run_one(Job((YOUBOT,), "scene", "pybullet", max_ticks=5), "replan", 0.0, 0)
    assert row["error"] == "RuntimeError: the planner broke"
    assert not row["success"] and row["method"] == "replan"

