"""Finishing a halted action that does not interfere with the next (btplan.acting.departures.finish)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from btplan import run
from btplan.acting import ACTING_OPTIONS
from btplan.acting.departures.finish import FinishFirst
from btplan.acting.offline import load
from btplan.bt import RUNNING
from btplan.bt.world import LeafKey
from btplan.model import GroundAction, Task
from btplan.sweep.scenarios import resolve
from btplan.worlds.symbolic import SymbolicWorld
from tests.presets import departures

ROOT = Path(__file__).resolve().parents[2]

TWO_TRUCKS = """
problem two_trucks for logistics {
    objects {
        city1 : city
        city1_airport : airport
        city1_loc1 : location
        truck1, truck2 : truck
        pkg1 : package
    }
    init {
        in_city(city1_airport, city1) in_city(city1_loc1, city1)
        at(truck1, city1_airport) at(truck2, city1_airport) at(pkg1, city1_airport)
    }
    goal { at(pkg1, city1_loc1) }
}
"""

DRIVE1: LeafKey = ("drive_truck", ("truck1", "city1_airport", "city1_loc1", "city1"))
DRIVE2: LeafKey = ("drive_truck", ("truck2", "city1_airport", "city1_loc1", "city1"))
LOAD1: LeafKey = ("load_truck", ("pkg1", "truck1", "city1_airport"))


def _setup(tmp_path: Path) -> tuple[SymbolicWorld, FinishFirst]:
    path = tmp_path / "two_trucks.bt"
    path.write_text(TWO_TRUCKS)
    task = resolve("packages").prepare(  # actions of two ticks
        load(str(ROOT / "domains" / "logistics.bt"), str(path), problem="two_trucks"))
    world = SymbolicWorld(task)
    grounding: dict[LeafKey, GroundAction] = {k: world.ground(k) for k in (DRIVE1, DRIVE2, LOAD1)}
    return world, FinishFirst(world, grounding)


def test_an_independent_action_is_finished_before_the_next_starts(tmp_path: Path) -> None:
    world, finishing = _setup(tmp_path)
    assert finishing.start(DRIVE1) is RUNNING
    finishing.end_tick()
    finishing.halt(DRIVE1)  # the tree turns to the other truck
    assert finishing.start(DRIVE2) is RUNNING
    finishing.end_tick()
    assert [str(a) for a in world.executed] == [
        "drive_truck(truck1, city1_airport, city1_loc1, city1)"]
    assert world.halted == []
    assert [a.args[0] for a in world.started] == ["truck1", "truck2"]


def test_the_tree_may_start_the_next_before_it_halts(tmp_path: Path) -> None:
    world, finishing = _setup(tmp_path)
    finishing.start(DRIVE1)
    finishing.end_tick()
    assert finishing.start(DRIVE2) is RUNNING  # a Sequence halts the later child after
    finishing.halt(DRIVE1)
    finishing.end_tick()
    assert len(world.executed) == 1 and world.halted == []


def test_an_interfering_action_is_halted(tmp_path: Path) -> None:
    world, finishing = _setup(tmp_path)
    finishing.start(DRIVE1)
    finishing.end_tick()
    finishing.halt(DRIVE1)
    finishing.start(LOAD1)  # needs the truck where the drive takes it from
    finishing.end_tick()
    assert [str(a) for a in world.halted] == [
        "drive_truck(truck1, city1_airport, city1_loc1, city1)"]
    assert world.executed == []


def test_a_halt_with_nothing_started_instead_stands(tmp_path: Path) -> None:
    world, finishing = _setup(tmp_path)
    finishing.start(DRIVE1)
    finishing.end_tick()
    finishing.halt(DRIVE1)
    finishing.end_tick()
    assert len(world.halted) == 1 and world.executed == []


def _packages(finish_first: bool, seed: int) -> tuple[int, int]:
    scenario = resolve("packages")
    task: Task = scenario.prepare(load(str(ROOT / "bench" / "problems" / "logistics_1.bt")))
    world = SymbolicWorld(task, seed=seed)
    outcome = run(task, world=world, agents=scenario.agents(task, 0.3, seed), seed=seed,
                  max_ticks=400,
                  config=departures(replace(ACTING_OPTIONS, expansions_per_tick=64),
                                    look_ahead=True, scope_moves=True, goal_credit=True,
                                    finish_first=finish_first))
    assert outcome.reached
    return outcome.ticks, len(world.halted)


def test_fewer_halts_and_ticks_on_packages_under_disturbance() -> None:
    ticks, halts = _packages(False, seed=2)
    finished_ticks, finished_halts = _packages(True, seed=2)
    assert finished_halts < halts
    assert finished_ticks < ticks


TWIN = """
domain twin {
    types { door }
    predicates { open(d: door) }
    action Key(d: door) {
        post: open(d)
        duration: 2
    }
    action Button(d: door) {
        post: open(d)
        duration: 2
    }
}
problem shut for twin {
    objects { front : door }
    init { }
    goal { open(front) }
}
"""


def test_an_action_whose_work_the_finished_one_did_is_not_started(tmp_path: Path) -> None:
    """The key opens the door while the button waits: the button is not pressed then."""
    path = tmp_path / "twin.bt"
    path.write_text(TWIN)
    task = load(str(path))
    world = SymbolicWorld(task)
    key, button = ("Key", ("front",)), ("Button", ("front",))
    finishing = FinishFirst(world, {k: world.ground(k) for k in (key, button)})
    assert finishing.start(key) is RUNNING
    finishing.end_tick()
    finishing.halt(key)  # the tree turns to the button: the key's turn is finished first
    assert finishing.start(button) is RUNNING
    finishing.end_tick()
    assert [str(a) for a in world.executed] == ["Key(front)"]
    assert [str(a) for a in world.started] == ["Key(front)"]  # the button was never pressed
