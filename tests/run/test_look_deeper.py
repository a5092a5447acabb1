"""Looking one level deeper (btplan.acting.departures.ahead): a later condition's achiever that
needs what is about to be held is dealt with before it is held."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from btplan import run
from btplan.acting import ACTING_OPTIONS, RunOutcome
from btplan.acting.departures.ahead import forced_out
from btplan.acting.offline import load
from btplan.bt import Sequence
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex, Judge
from btplan.planner.expand import condition_node
from tests.presets import departures

ROOT = Path(__file__).resolve().parents[2]
DOMAINS = ROOT / "domains"
OPTIONS = replace(ACTING_OPTIONS, expansions_per_tick=64)

DOOR = """
domain door {
    types { place, thing }
    constants { home, goal : place }
    predicates {
        at(p: place)
        holding(t: thing)
        hand_empty
        on(t: thing, p: place)
        open
    }
    action Go(p: place) {
        pre:  open
        post: not at(_), at(p)
        duration: 2
    }
    action Pick(t: thing, p: place) {
        pre:  hand_empty, at(p), on(t, p)
        post: holding(t), not hand_empty, not on(t, p)
        duration: 2
    }
    action Put(t: thing, p: place) {
        pre:  holding(t), at(p)
        post: on(t, p), hand_empty, not holding(t)
        duration: 2
    }
    action Open() {
        pre:  hand_empty, at(home)
        post: open
        duration: 2
    }
    OTHER_WAY
}

problem carry for door {
    objects { box : thing }
    init { at(home) hand_empty on(box, home) }
    goal { on(box, goal) }
}
"""
"""The box must be carried through a closed door, and opening it takes both hands."""

KICK = """action Kick() {
        pre:  at(home)
        post: open
        cost: 5
        duration: 2
    }"""
"""A way to open the door with the box in hand."""

BLOCKED = """
problem blocked_from_the_start for pick_place_obstacle {
    objects {
        cube, sphere : object
        aside : location
        tau_cube, tau_goal, tau_sphere, tau_aside : trajectory
    }
    init {
        hand_empty blocks(sphere, tau_goal)
        target(goal), target(aside)
        route(cube, tau_cube), route(goal, tau_goal), route(sphere, tau_sphere)
        route(aside, tau_aside)
    }
    goal { on(cube, goal) }
}
"""
"""Example 2 with the sphere on the way to the goal before the robot sets off."""


def door(tmp_path: Path, other_way: str = "") -> Task:
    path = tmp_path / "door.bt"
    path.write_text(DOOR.replace("OTHER_WAY", other_way))
    return load(str(path))


def acted(task: Task) -> RunOutcome:
    outcome = run(task, config=departures(OPTIONS, look_ahead=True, scope_moves=True),
                  max_ticks=100)
    assert outcome.reached
    return outcome


def first_tick(outcome: RunOutcome) -> dict[str, int]:
    """The conditions expanded in the first tick, with the moves each took."""
    return {e.condition: e.moves for e in outcome.records[0].expansions}


def test_the_door_is_opened_before_the_box_fills_the_hand(tmp_path: Path) -> None:
    outcome = acted(door(tmp_path))
    assert [str(a) for a in outcome.executed] == [
        "Open()", "Pick(box, home)", "Go(goal)", "Put(box, goal)"]
    assert first_tick(outcome)["open()"] > 0  # expanded at once, and moved in front


def test_a_deeper_condition_with_a_way_that_fits_waits_for_the_tick(tmp_path: Path) -> None:
    outcome = acted(door(tmp_path, KICK))
    assert "open()" not in first_tick(outcome)
    assert [str(a) for a in outcome.executed] == [
        "Pick(box, home)", "Kick()", "Go(goal)", "Put(box, goal)"]


def test_the_path_is_cleared_before_the_cube_is_taken(tmp_path: Path) -> None:
    path = tmp_path / "blocked.bt"
    path.write_text(BLOCKED)
    task = load(str(DOMAINS / "pick_place_obstacle.bt"), str(path),
                problem="blocked_from_the_start")
    steps = [str(a) for a in acted(task).executed]
    assert steps == ["MoveTo(sphere, tau_sphere)", "Pick(sphere)", "MoveTo(aside, tau_aside)",
                     "Place(sphere, aside)", "MoveTo(cube, tau_cube)", "Pick(cube)",
                     "MoveTo(goal, tau_goal)", "Place(cube, goal)"]


def test_forced_out_asks_every_achiever(tmp_path: Path) -> None:
    task = door(tmp_path, KICK)
    holding, at_goal = (condition_node(GroundLiteral(Atom(name, args), True), task)
                        for name, args in (("holding", ("box",)), ("at", ("goal",))))
    Sequence([holding, at_goal])  # Go(goal), for at(goal), runs with the box in hand
    index = AchieverIndex(task, OPTIONS)
    domain = task.domain.action_map
    open_door, kick = (index.ground(domain[name], ()) for name in ("Open", "Kick"))
    judge = Judge({}, index.mutexes)
    assert forced_out(at_goal, [open_door], judge)  # it needs the hand the box fills
    assert not forced_out(at_goal, [open_door, kick], judge)  # a kick does not
    assert not forced_out(holding, [open_door], judge)  # nothing is held before it
    assert not forced_out(at_goal, [], judge)
    assert not forced_out(at_goal, [open_door], judge, lambda held: True)  # on the way


@pytest.mark.parametrize("other_way", ["", KICK])
def test_without_the_look_ahead_only_a_forcing_condition_is_expanded_early(
        tmp_path: Path, other_way: str) -> None:
    outcome = run(door(tmp_path, other_way),
                  config=departures(OPTIONS, look_deeper=True, scope_moves=True), max_ticks=100)
    assert outcome.reached
    steps = [str(a) for a in outcome.executed]
    if other_way:  # Go(goal) fits with the box in hand: at(goal) waits for the tick
        assert "at(goal)" not in first_tick(outcome)
        assert steps == ["Pick(box, home)", "Kick()", "Go(goal)", "Put(box, goal)"]
    else:
        assert first_tick(outcome)["open()"] > 0
        assert steps == ["Open()", "Pick(box, home)", "Go(goal)", "Put(box, goal)"]


def test_a_condition_on_the_way_to_what_is_held_is_left_to_the_tick() -> None:
    """b3 lies under b4 under b6: clearing b4 (for on(b1, b4)) conflicts with on(b3, b6),
    but stacking b3 clears b4 on its way, so it is not expanded a second time ahead."""
    task = load(str(ROOT / "bench" / "problems" / "blocksworld_6.bt"))
    outcome = run(task, config=departures(OPTIONS, look_ahead=True, scope_moves=True,
                                          goal_credit=True), max_ticks=100)
    assert outcome.reached
    conditions = [e.condition for r in outcome.records for e in r.expansions]
    assert conditions.count("clear(b4)") == 1
