"""A slow failure hands over to the next alternative (ActingConfig.wait_for_alternatives).

On a robot an action fails ticks after it starts. A reactive Fallback ticks its first
child again at the next tick: without waiting for the alternative, the failed action
is started again and the alternative halted, every time."""

from __future__ import annotations

from pathlib import Path

import btplan
from btplan.acting.config import ActingConfig
from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.robot import Robot, action, condition

TASK = btplan.load(str(Path(__file__).resolve().parents[2] / "domains" / "run_alternatives.bt"))


class Slow:
    """A skill that ends on its `polls`-th poll, with `ok` (and then `done()`)."""

    def __init__(self, polls: int, ok: bool, done: object = None) -> None:
        self.left, self.ok, self.done = polls, ok, done

    def poll(self) -> Status:
        self.left -= 1
        if self.left > 0:
            return RUNNING
        if self.ok and self.done is not None:
            self.done()  # type: ignore[operator]
        return SUCCESS if self.ok else FAILURE


class Parcel(Robot):
    """The road is closed: Drive fails after three polls; Fly succeeds after three."""

    def __init__(self) -> None:
        self.loaded = self.delivered = False
        self.flights = 0
        super().__init__()

    @condition("loaded")
    def is_loaded(self, p: str) -> bool:
        return self.loaded

    @condition("delivered")
    def is_delivered(self, p: str) -> bool:
        return self.delivered

    @action("Load")
    def load(self, p: str) -> Slow:
        return Slow(1, True, lambda: setattr(self, "loaded", True))

    @action("Drive")
    def drive(self, p: str) -> Slow:
        return Slow(3, False)

    @action("Fly")
    def fly(self, p: str) -> Slow:
        self.flights += 1

        def landed() -> None:
            self.delivered, self.loaded = True, False

        return Slow(3, True, landed)


def test_the_alternative_runs_to_its_end() -> None:
    robot = Parcel()
    outcome = btplan.run(TASK, world=robot, max_ticks=100)
    assert outcome.reached and robot.flights == 1
    assert outcome.summary().count("halted") == 0
    assert [str(a) for a in outcome.executed] == ["Load(box)", "Fly(box)"]


def test_without_waiting_the_failed_action_starves_its_alternative() -> None:
    robot = Parcel()
    outcome = btplan.run(TASK, world=robot, max_ticks=100,
                         config=ActingConfig.default(wait_for_alternatives=False))
    assert not outcome.reached and robot.flights > 10
    assert outcome.summary().count("halted") > 10
