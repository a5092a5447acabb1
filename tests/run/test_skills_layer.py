"""The loop's layer between the tree and the robot: one run of a grounded action at a time,
effects observed before SUCCESS, facts in any shape, a fixed rate on a clock, and runs
that go on after the goal with flat memory."""

from __future__ import annotations

from pathlib import Path

import btplan
from btplan.acting.clock import FakeClock
from btplan.acting.records import LISTED
from btplan.acting.skills import Skills
from btplan.bt import RUNNING, SUCCESS, LeafKey, Status
from btplan.worlds.symbolic import SymbolicWorld

ROOT = Path(__file__).resolve().parents[2]
TASK = btplan.load(str(ROOT / "domains" / "pick_place.bt"))
MOVE: LeafKey = ("MoveTo", ("cube", "tau_cube"))


class Calls:
    """A world that logs every call and keeps a skill running until told otherwise."""

    def __init__(self) -> None:
        self.calls: list[tuple[str, str]] = []

    def check(self, key: LeafKey) -> bool:
        return False

    def start(self, key: LeafKey) -> Status:
        self.calls.append(("start", key[0]))
        return RUNNING

    def step(self, key: LeafKey) -> Status:
        self.calls.append(("step", key[0]))
        return RUNNING

    def halt(self, key: LeafKey) -> None:
        self.calls.append(("halt", key[0]))

    def facts(self) -> list[tuple[str, str]]:
        return [("near", "cube"), ("hand_empty",)]


def test_two_leaves_naming_one_action_run_one_skill() -> None:
    world = Calls()
    skills = Skills(world, {})
    skills.begin_tick()
    assert skills.start(MOVE) is RUNNING
    assert skills.start(MOVE) is RUNNING  # the second leaf: the same skill, not a new one
    skills.halt(MOVE)  # the first leaf, no longer reached: the other one runs it
    skills.begin_tick()
    assert skills.step(MOVE) is RUNNING
    assert world.calls == [("start", "MoveTo"), ("step", "MoveTo")]


def test_a_step_after_a_halt_starts_the_skill_again() -> None:
    world = Calls()
    skills = Skills(world, {})
    skills.begin_tick()
    skills.start(MOVE)
    skills.begin_tick()
    skills.halt(MOVE)
    skills.halt(MOVE)  # halting what no longer runs sends nothing
    assert skills.step(MOVE) is RUNNING  # a leaf that still thinks it runs
    assert world.calls == [("start", "MoveTo"), ("halt", "MoveTo"), ("start", "MoveTo")]


def test_facts_may_be_plain_tuples() -> None:
    skills = Skills(Calls(), {})
    facts = skills.facts()
    assert {str(a) for a in facts} == {"near(cube)", "hand_empty()"}
    assert skills.facts() is facts  # the same object while the state is the same


class Eager(SymbolicWorld):
    """Asynchronous skills: the effects show a tick before the skill says SUCCESS."""

    def step(self, key: LeafKey) -> Status:
        status = super().step(key)
        if status is SUCCESS and key[0] == "MoveTo":
            return RUNNING  # finished in the world, not yet reported
        return status


def test_an_action_whose_effects_show_first_is_finished_not_halted() -> None:
    outcome = btplan.run(TASK, world=Eager(TASK))
    total = outcome.summary()
    assert outcome.reached and total.halted == []
    assert total.observed == ["MoveTo(cube, tau_cube)", "MoveTo(goal, tau_goal)"]
    assert [str(a) for a in outcome.executed] == [
        "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]
    line = next(r for r in outcome.records if r.observed).to_dict()
    assert line["observed"] == ["MoveTo(cube, tau_cube)"]


class Slow(SymbolicWorld):
    """A world whose fourth tick takes a quarter of a second of the clock's time."""

    def __init__(self, task: object, clock: FakeClock) -> None:
        super().__init__(task)  # type: ignore[arg-type]
        self.clock, self.steps = clock, 0

    def step(self, key: LeafKey) -> Status:
        self.steps += 1
        if self.steps == 3:
            self.clock.advance(0.25)
        return super().step(key)


def test_ticks_keep_a_fixed_rate_and_late_ticks_are_counted() -> None:
    clock = FakeClock()
    outcome = btplan.run(TASK, world=Slow(TASK, clock), rate=10, clock=clock)
    assert outcome.reached
    total = outcome.summary()
    assert total.overruns == 1 and abs(total.worst_lateness - 0.15) < 1e-9
    # 7 ticks, 0.1 s apart, and the one that started late did not make the next ones burst
    assert abs(clock.now() - (0.6 + 0.15)) < 1e-9


def test_a_run_kept_after_the_goal_achieves_it_again_when_it_is_undone() -> None:
    outcome = btplan.run(TASK, keep=True, max_ticks=30, disturb=["undo:Place@12"])
    total = outcome.summary()
    assert outcome.reached and outcome.ticks == 30
    assert total.goal_reached == [7, 13] and total.goal_lost == [12]
    marks = [(r.tick, r.to_dict().get("goal")) for r in outcome.records if r.goal]
    assert marks == [(7, "reached"), (12, "lost"), (13, "reached")]


def test_a_long_run_keeps_counts_not_lists() -> None:
    world = SymbolicWorld(TASK, failure_probability={"Place": 1.0})
    ticks = LISTED + 2_000
    outcome = btplan.run(TASK, world=world, max_ticks=ticks)
    total = outcome.summary()
    assert not outcome.reached and total.ticks == ticks
    assert len(total.failed) == LISTED < total.count("failed")
    assert len(outcome.records) <= 10_000


def test_a_kept_run_stopped_with_the_goal_holding_counts_as_reached() -> None:
    ticks: list[int] = []
    outcome = btplan.run(TASK, keep=True, max_ticks=None, stop=lambda: len(ticks) == 12,
                         view=lambda root, statuses, record: ticks.append(record.tick))
    assert outcome.interrupted and outcome.reached and outcome.ticks == 12


class Mutable(SymbolicWorld):
    """A world that hands out the same set object, changed in place."""

    def __init__(self, task: object) -> None:
        super().__init__(task)  # type: ignore[arg-type]
        self.shared: set[object] = set()

    def facts(self) -> frozenset:  # type: ignore[type-arg, override]
        self.shared.clear()
        self.shared.update(super().facts())
        return self.shared  # type: ignore[return-value]


def test_a_state_changed_in_place_is_read_again() -> None:
    assert btplan.run(TASK, world=Mutable(TASK)).reached


def test_a_world_whose_state_cannot_be_read_ends_the_run_with_a_world_error() -> None:
    import pytest

    from btplan.errors import WorldError

    class Mute(SymbolicWorld):
        def facts(self) -> frozenset:  # type: ignore[type-arg]
            raise OSError("the state topic is gone")

    with pytest.raises(WorldError, match="Mute.facts.. raised OSError: the state topic is gone"):
        btplan.run(TASK, world=Mute(TASK))


def test_effects_another_action_made_are_not_credited_to_a_running_skill() -> None:
    """The door the key opened while the button's press still ran: the press is halted,
    not finished by observation."""
    from btplan.model import Atom, GroundAction

    press = GroundAction(name="Press", add=(Atom("open", ()),))
    unlock = GroundAction(name="Unlock", add=(Atom("open", ()),))

    class Opened(Calls):
        def step(self, key: LeafKey) -> Status:
            return SUCCESS if key[0] == "Unlock" else RUNNING

        def facts(self) -> list[tuple[str, str]]:
            return [("open",)]

    skills = Skills(Opened(), {press.key: press, unlock.key: unlock})
    skills.begin_tick()
    skills.start(press.key)
    skills.start(unlock.key)
    skills.begin_tick()
    assert skills.step(unlock.key) is SUCCESS
    skills.halt(press.key)
    events = skills.take_events()
    assert [str(a) for a in events.halted] == ["Press()"] and events.observed == []


def test_a_loop_stuck_online_acts_on_a_tree_planned_offline_from_the_state_of_now() -> None:
    """The Sussman anomaly: one online attempt finds no conflict-free place; offline
    planning, from the facts the world reports then, finds the tree the loop goes on with."""
    from btplan.acting.config import ActingConfig
    from btplan.lang import load
    from btplan.records import replace

    task = load([str(ROOT / "domains" / "blocksworld.bt")], problem="sussman")
    online = ActingConfig.default(plan_before_acting=False)
    alone = btplan.run(task, config=replace(online, plan_offline_when_stuck=False))
    assert not alone.reached and "conflict-free" in alone.reason
    outcome = btplan.run(task, config=online)
    assert outcome.reached
    fell_back = [r for r in outcome.records if r.status == "FAILURE" and r.expansions]
    assert len(fell_back) == 1  # the offline plan's expansions, on the tick it was made
    assert outcome.summary().count("halted") == 0
