"""The symbolic world: durations, effects, failures, external changes and refinement."""

from __future__ import annotations

from btplan.bt import FAILURE, RUNNING, SUCCESS
from btplan.lang import load
from btplan.model import Atom
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS


def world(**kwargs: object) -> SymbolicWorld:
    return SymbolicWorld(load([str(DOMAINS / "pick_place.bt")]), **kwargs)  # type: ignore[arg-type]


def test_an_action_runs_for_its_duration_then_applies_its_effects() -> None:
    w = world()
    key = ("MoveTo", ("cube", "tau_cube"))
    assert w.start(key) is RUNNING
    assert w.step(key) is RUNNING
    assert ("near", ("cube",)) not in w.facts()
    assert w.step(key) is SUCCESS
    assert Atom("near", ("cube",)) in w.facts()
    assert [str(a) for a in w.executed] == ["MoveTo(cube, tau_cube)"]


def test_wildcard_delete_moves_the_robot() -> None:
    w = world()
    w.set_fact(Atom("near", ("cube",)))
    w.apply_action(w.ground(("MoveTo", ("goal", "tau_goal"))))
    assert w.check(("near", ("goal",))) and not w.check(("near", ("cube",)))


def test_an_action_fails_when_its_precondition_stops_holding() -> None:
    w = world()
    key = ("MoveTo", ("cube", "tau_cube"))
    assert w.start(key) is RUNNING
    w.clear_fact(Atom("free", ("tau_cube",)))
    assert w.step(key) is FAILURE
    assert [str(a) for a in w.failed] == ["MoveTo(cube, tau_cube)"] and not w.executed


def test_fail_next_fails_one_matching_tick_only() -> None:
    w = world()
    w.set_fact(Atom("near", ("cube",)))
    w.fail_next("Pick")
    assert w.start(("Pick", ("cube",))) is FAILURE
    assert w.start(("Pick", ("cube",))) is RUNNING


def test_failure_probability_is_seeded() -> None:
    def outcomes(seed: int) -> list[str]:
        w = world(seed=seed, failure_probability={"MoveTo": 0.5})
        return [w.start(("MoveTo", ("cube", "tau_cube"))).value for _ in range(20)]

    assert outcomes(3) == outcomes(3)
    assert "FAILURE" in outcomes(3) and "RUNNING" in outcomes(3)


def test_halt_records_and_forgets_the_running_action() -> None:
    w = world()
    key = ("MoveTo", ("cube", "tau_cube"))
    w.start(key)
    w.halt(key)
    assert [str(a) for a in w.halted] == ["MoveTo(cube, tau_cube)"]
    assert w.start(key) is RUNNING  # starts afresh


def test_refine_answers_objects_satisfying_where_in_the_current_state() -> None:
    w = world()
    move = w.task.domain.action_map["MoveTo"]
    trajectory = move.parameters[1]
    assert w.refine(move, {"l": "goal"}, trajectory) == ["tau_goal"]
    w.set_fact(Atom("route", ("goal", "tau_cube")))
    assert w.refine(move, {"l": "goal"}, trajectory) == ["tau_cube", "tau_goal"]
    w.clear_fact(Atom("route", ("goal", "tau_cube")))  # what is remembered is not the state
    assert w.refine(move, {"l": "goal"}, trajectory) == ["tau_goal"]
    # a second type in the same world gets its own objects (the goal names both
    # locations, so neither is held back)
    place = w.task.domain.action_map["Place"]
    location = place.parameters[1]
    assert w.refine(place, {"o": "cube"}, location) == ["cube", "goal"]
    assert w.refine(move, {"l": "goal"}, trajectory) == ["tau_goal"]


def test_equality_conditions_are_checked_by_value() -> None:
    w = world()
    assert w.check(("=", ("a", "a"))) and not w.check(("=", ("a", "b")))


def test_facts_is_one_object_until_the_state_changes() -> None:
    """Planning finds what it remembers per state by the state's identity: the world
    hands out the same frozen state while nothing changes, and a fresh one after every
    kind of change (an outside fact set or cleared, an outside action, a finished one)."""
    w = world()
    first = w.facts()
    assert w.facts() is first
    w.set_fact(Atom("near", ("cube",)))
    second = w.facts()
    assert second is not first and Atom("near", ("cube",)) in second
    assert w.facts() is second
    w.clear_fact(Atom("near", ("cube",)))
    third = w.facts()
    assert third == first and third is not second
    w.apply_action(w.ground(("MoveTo", ("goal", "tau_goal"))))
    fourth = w.facts()
    assert Atom("near", ("goal",)) in fourth and fourth is not third
    key = ("MoveTo", ("cube", "tau_cube"))
    assert w.start(key) is RUNNING
    assert w.facts() is fourth  # running changes nothing yet
    w.step(key)
    assert w.step(key) is SUCCESS
    assert Atom("near", ("cube",)) in w.facts() and w.facts() is not fourth
    assert fourth == frozenset(fourth)  # earlier states are left as they were
    assert Atom("near", ("goal",)) in fourth


def test_the_action_logs_keep_their_recent_part_only() -> None:
    """A run of a million ticks must not keep a million entries (btplan.worlds.logs)."""
    from btplan.worlds.logs import KEPT

    w = world()
    key = ("MoveTo", ("cube", "tau_cube"))
    for _ in range(KEPT + 2_500):
        w.start(key)
        w.halt(key)
    assert KEPT <= len(w.started) <= KEPT + 1000 and KEPT <= len(w.halted) <= KEPT + 1000
    w.start(key)
    assert [str(a) for a in w.running_actions()] == ["MoveTo(cube, tau_cube)"]
