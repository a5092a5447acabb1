"""Going round in circles is told apart from facts that come and go while an action runs."""

from __future__ import annotations

from pathlib import Path

from btplan.acting.loop import BlendedLoop
from btplan.bt import RUNNING, Condition, Status
from btplan.bt.leaves import LeafKey
from btplan.lang import load
from btplan.model import Atom
from btplan.robot import Capabilities
from btplan.worlds.symbolic import SymbolicWorld

DOMAIN = Path(__file__).resolve().parents[2] / "domains" / "pick_place.bt"
PASSING = Atom("near", ("cube",))


class Flicker(SymbolicWorld):
    """As in a simulator: while the robot drives to the goal, it passes the cube again,
    so `near(cube)` comes and goes with nothing completed in between."""

    capabilities = Capabilities(refines=True, continuous=True)

    def step(self, key: LeafKey) -> Status:
        status = super().step(key)
        if status is RUNNING and key[0] == "MoveTo" and key[1][0] == "goal":
            if PASSING in self.facts():
                self.clear_fact(PASSING)
            else:
                self.set_fact(PASSING)
        return status


def test_facts_that_flicker_while_an_action_runs_are_not_a_loop() -> None:
    task = load([str(DOMAIN)])
    slow = tuple(a.model_copy(update={"duration": 6}) if a.name == "MoveTo" else a
                 for a in task.domain.actions)
    task = task.model_copy(update={"domain": task.domain.model_copy(update={"actions": slow})})
    world = Flicker(task)
    result = BlendedLoop(task, world).run(100)
    assert result.reached
    assert [str(a) for a in world.executed][-1] == "Place(cube, goal)"


class _World:
    """A stand-in world for `Circles`: only the counters the check reads."""

    capabilities = Capabilities(outside_changes=True, lessons=True)
    outside_changes = 0
    lessons = 0


class _Skills:
    """The loop's view of `_World`, as `Circles` reads it: no action has ended."""

    def __init__(self, world: _World) -> None:
        self.world, self.capabilities, self.ended = world, world.capabilities, 0


def test_a_state_seen_again_after_a_new_lesson_is_not_a_loop() -> None:
    from btplan.acting.progress import Circles

    world = _World()
    circles, skills = Circles(), _Skills(world)
    near, away = frozenset({PASSING}), frozenset()
    assert not circles.repeated(skills, away, near, 3)  # type: ignore[arg-type]
    assert not circles.repeated(skills, near, away, 3)  # type: ignore[arg-type]
    world.lessons = 1  # the world learned that the last try cannot work: another follows
    assert not circles.repeated(skills, away, near, 3)  # type: ignore[arg-type]
    assert not circles.repeated(skills, near, away, 3)  # type: ignore[arg-type]
    assert circles.repeated(skills, away, near, 3)  # type: ignore[arg-type]  # a loop


def test_the_conflict_judge_is_made_again_when_guards_or_the_state_change() -> None:
    """`judge()` is kept while nothing it reads changed; a new guard or a new state
    gives a new one that knows it."""
    task = load([str(DOMAIN)])
    world = SymbolicWorld(task)
    loop = BlendedLoop(task, world)
    first = loop.judge()
    assert loop.judge() is first
    assert first.state == world.facts()
    guard = Condition("near", ("cube",))
    loop.never_expand([guard])
    second = loop.judge()
    assert second is not first and guard in second.guards and guard not in first.guards
    assert loop.judge() is second
    loop.never_expand([guard])  # already known: nothing changed
    assert loop.judge() is second
    world.set_fact(PASSING)
    third = loop.judge()
    assert third is not second and third.state == world.facts() and PASSING in third.state
    assert third.guards == second.guards


class Remeasured(SymbolicWorld):
    """As in a simulator whose move re-plans its path once halted: the tick finds the
    way not free once, on the old path, while the facts read after it say it is."""

    first = True

    def check(self, key: LeafKey) -> bool:
        if key == ("free", ("tau_goal",)) and self.first:
            self.first = False
            return False
        return super().check(key)


def test_a_failed_condition_the_facts_say_holds_is_left_for_the_next_tick() -> None:
    task = load([str(DOMAIN)])
    world = Remeasured(task)
    result = BlendedLoop(task, world).run(100)
    assert not world.first and result.reached  # no achiever was sought for free(tau_goal)
