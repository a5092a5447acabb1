"""A paced run waits for a dead end to pass before it counts as stuck (ActingConfig.stuck_wait).

The robot's gripper sensor answers at once, its grasp sensor some ticks late: when Pick
ends, the hand reads not empty while the cube does not read held yet, a state from
which nothing leads to the goal. The run must wait for the late reading, not end."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

import btplan
from btplan.acting import ActingConfig, FakeClock
from btplan.acting.stuck_wait import StuckWait
from btplan.bt import FAILURE, RUNNING, SUCCESS, Status
from btplan.errors import NoAchieverError
from btplan.robot import Robot

ROOT = Path(__file__).resolve().parents[2]
TASK = btplan.load(str(ROOT / "domains" / "pick_place.bt"))
RATE = 10
LAG = 0.35
"""Seconds the grasp sensor lags behind the gripper sensor: four ticks at RATE."""


class Ticks:
    """A skill done at its second poll, when it changes the robot's state."""

    def __init__(self, done: Callable[[], None]) -> None:
        self.done, self.polls = done, 0

    def poll(self) -> Status | None:
        self.polls += 1
        if self.polls < 2:
            return None  # running
        self.done()
        return SUCCESS

    def cancel(self) -> None:
        pass


class LateGrasp:
    """pick_place's changing facts, with `holding` read LAG seconds late."""

    def __init__(self, clock: FakeClock, lag: float = LAG) -> None:
        self.clock, self.lag = clock, lag
        self.near: str | None = None
        self.held: str | None = None
        self.held_since = 0.0
        self.cube: str | None = None

    def robot(self) -> Robot:
        robot = Robot()
        robot.condition("on")(lambda o, l: self.cube == l)
        robot.condition("holding")(
            lambda o: self.held == o and self.clock.now() >= self.held_since + self.lag)
        robot.condition("hand_empty")(lambda: self.held is None)
        robot.condition("near")(lambda l: self.near == l or l == self.held)
        robot.action("MoveTo")(self.move)
        robot.action("Pick")(self.pick)
        robot.action("Place")(self.place)
        return robot

    def move(self, l: str, t: str) -> Ticks:
        return Ticks(lambda: setattr(self, "near", l))

    def pick(self, o: str) -> Ticks:
        def grasp() -> None:
            self.held, self.held_since = o, self.clock.now()
        return Ticks(grasp)

    def place(self, o: str, l: str) -> Ticks:
        def release() -> None:
            self.held, self.cube = None, l
        return Ticks(release)


def act(config: ActingConfig, lag: float = LAG) -> btplan.RunOutcome:
    clock = FakeClock()
    return btplan.run(TASK, world=LateGrasp(clock, lag).robot(), rate=RATE, clock=clock,
                      max_ticks=100, config=config)


def test_the_run_waits_for_the_late_reading_and_reaches_the_goal() -> None:
    outcome = act(ActingConfig.default())
    assert outcome.reached, outcome.reason
    assert [str(a) for a in outcome.executed] == [
        "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]


def test_without_the_wait_the_same_run_ends_stuck() -> None:
    outcome = act(ActingConfig.default(stuck_wait=0.0))
    assert not outcome.reached
    assert "hand_empty" in outcome.reason


def test_a_dead_end_that_lasts_ends_the_run_once_the_wait_is_up() -> None:
    outcome = act(ActingConfig.default(stuck_wait=0.5), lag=60.0)  # the cube never reads held
    assert not outcome.reached
    assert "hand_empty" in outcome.reason
    stuck_from = next(r.tick for r in outcome.records if r.status == "FAILURE")
    # ticks on for half a second (5 ticks; one more where the clock's sums round down)
    assert 0.5 * RATE <= outcome.ticks - stuck_from <= 0.5 * RATE + 1


def test_the_wait_ends_with_a_tick_that_does_not_fail_or_with_its_time() -> None:
    clock, error = FakeClock(), NoAchieverError("stuck")
    wait = StuckWait(0.5, clock)
    assert wait.holds(error)
    clock.advance(0.3)
    wait.after(FAILURE)  # still within the time
    wait.after(RUNNING)  # the dead end passed: the wait is over
    clock.advance(0.3)
    assert wait.holds(error)  # a new dead end, a new wait
    clock.advance(0.5)
    with pytest.raises(NoAchieverError):
        wait.after(FAILURE)
    assert not wait.holds(error)  # over: the run ends (or plans offline) ...
    assert wait.holds(error)  # ... and a later dead end gets its own wait
    assert not StuckWait(0.5, None).holds(error)  # no clock: no wait
