"""A fake fetch robot for domains/pick_place.bt, written with btplan's robot API.

Its skills run in threads for a few tenths of a second, as blocking driver calls
would; Pick slips now and then (seeded); a halted skill stops early. Act with it:

    btplan run domains/pick_place.bt --world examples/my_robot.py:FetchRobot --hz 10

or run this file, which adds a passer-by who knocks the cube out of the gripper once.
docs/robot.md explains each part.
"""

from __future__ import annotations

import random
import threading
from pathlib import Path

import btplan
from btplan.robot import Robot, action, condition
from btplan.worlds.agents import Disturbance

DOMAIN = Path(__file__).resolve().parents[1] / "domains" / "pick_place.bt"


class FetchRobot(Robot):
    """A base, a gripper and a cube, which the skills' threads move (two at once under
    `self.lock`)."""

    def __init__(self, seed: int = 0, fail: float = 0.2) -> None:
        super().__init__()  # collects the methods marked with @condition and @action
        self.random = random.Random(seed)  # seeded: the same slips on every run
        self.fail = fail  # the chance that a Pick slips
        self.lock = threading.Lock()
        self.base: str | None = "dock"  # None while the base drives
        self.cube: str | None = "table"  # None while the cube is in the gripper
        self.gripper: str | None = None

    def place_of(self, thing: str) -> str | None:
        """Where a location of the domain is: the cube moves, the goal does not."""
        if thing == "cube":
            return self.base if self.gripper == "cube" else self.cube
        return thing

    # Conditions answer for the predicates the actions change; the planner reads the
    # others (free, route) from the problem. They run in the loop's thread at every
    # tick, so they only read the state, and never wait.

    @condition("on")
    def on(self, o: str, l: str) -> bool:
        return o == "cube" and self.cube == l

    @condition("holding")
    def holding(self, o: str) -> bool:
        return self.gripper == o

    @condition("hand_empty")
    def hand_empty(self) -> bool:
        return self.gripper is None

    @condition("near")
    def near(self, l: str) -> bool:
        with self.lock:  # two fields read together: not halfway through a Pick
            return self.base is not None and self.base == self.place_of(l)

    # Actions get the grounded arguments in the template's order. A threaded action
    # runs in a thread of its own and may block; the loop polls it every tick. `stop`
    # is set when the tree halts it: `stop.wait(s)` sleeps and returns True at once then.

    @action("MoveTo", threaded=True)
    def move_to(self, l: str, t: str, stop: threading.Event) -> bool:
        # `t` is the trajectory btplan chose from route(l, t): tau_cube or tau_goal.
        target = self.place_of(l)
        self.base = None  # on the way: near nothing
        if stop.wait(0.4):
            return False  # halted: the base stops where it is
        self.base = target
        return True

    @action("Pick", threaded=True)
    def pick(self, o: str, stop: threading.Event) -> bool:
        if stop.wait(0.3):
            return False
        if self.random.random() < self.fail:
            # An exception is this action's FAILURE, with the message in the trace;
            # the tree tries again (or differently) at the next tick.
            raise RuntimeError(f"the {o} slipped out of the fingers")
        with self.lock:
            self.gripper, self.cube = o, None
        return True

    @action("Place", threaded=True)
    def place(self, o: str, l: str, stop: threading.Event) -> bool:
        if stop.wait(0.3):
            return False
        with self.lock:
            self.gripper, self.cube = None, self.place_of(l)
        return True


class PasserBy:
    """An external agent: acts before a tick, here once, three ticks into a carry."""

    name, carried = "passer-by", 0

    def act(self, robot: FetchRobot, tick: int) -> list[Disturbance]:
        if robot.gripper is None or self.carried < 0:
            return []
        self.carried += 1
        if self.carried < 3:
            return []
        with robot.lock:
            robot.gripper, robot.cube = None, "floor"
        self.carried = -1  # once
        return [Disturbance(tick, self.name, "knocked the cube to the floor", "undo")]


if __name__ == "__main__":
    task = btplan.load(str(DOMAIN))
    robot = FetchRobot(seed=1)
    outcome = btplan.run(task, world=robot, agents=[PasserBy()], rate=10, max_ticks=600)
    robot.close()  # the CLI closes a world itself; in Python, close what you made
    total = outcome.summary()
    print(f"reached: {outcome.reached} in {total.ticks} ticks ({outcome.reason})")
    for name in ("finished", "halted", "failed"):
        print(f"{name}: {', '.join(getattr(total, name)) or '-'}")
    print("errors:", "; ".join(f"{what}: {why}" for what, why in total.errors) or "-")
    print("disturbed:", "; ".join(f"@{d.tick} {d.description}" for d in total.disturbances))
