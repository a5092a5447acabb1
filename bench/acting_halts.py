"""Undisturbed acting runs beside the offline plan: what the loop halts, starts and executes.

A run with no disturbance has nothing to react to, so it should act like a plan: no
action halted, and no more actions executed than `btplan plan` finds. Each problem
runs once with the default preset (`btplan run`) and once with `ActingConfig.paper()`
(Algorithm 1 as published, one expansion per tick). Then a robot whose skills take
ticks and whose wall button always fails shows what a reactive Fallback does with a
slow failing alternative: the published loop halts the other alternative every time
it tries the button again, the default finishes it first.

    python bench/acting_halts.py                    # well under two minutes
    python bench/acting_halts.py --skill-ticks 3 --button-ticks 2 --robot-ticks 200
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import btplan
from btplan.acting.config import ActingConfig
from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.errors import PlanningError
from btplan.lang import parse_bt
from btplan.lang.generators import assembly, blocksworld, logistics
from btplan.model import Task
from btplan.robot import Robot, action, condition

DOMAINS = Path(__file__).resolve().parent.parent / "domains"
SEEDS = (1, 2, 3)
BLOCKS = (4, 5, 6)
PACKAGES = 3
PARTS = 6


@dataclass
class Acted:
    """One run, in the numbers the table shows."""

    executed: int
    halted: int
    started: int
    observed: int
    ticks: int
    reached: bool
    reason: str

    @classmethod
    def of(cls, outcome: btplan.RunOutcome) -> Acted:
        s = outcome.summary()
        return cls(len(outcome.executed), s.count("halted"), s.count("started"),
                   s.count("observed"), outcome.ticks, outcome.reached, outcome.reason)


@dataclass
class Row:
    problem: str
    plan: int
    raw: int
    default: Acted
    paper: Acted


# --- the problems ------------------------------------------------------------------------


def shipped() -> Iterator[tuple[str, Task]]:
    """Every problem of every shipped domain file, by file (and problem, when a file has
    several)."""
    for path in sorted([*DOMAINS.glob("*.bt"), *DOMAINS.glob("*.pddl")]):
        names: list[str | None] = [None]
        if path.suffix == ".bt":
            problems = parse_bt(path.read_text(), path.name).problems
            if len(problems) > 1:
                names = [p.name for p in problems]
        for name in names:
            label = path.name if name is None else f"{path.name}:{name}"
            yield label, btplan.load(str(path), problem=name)


def generated() -> Iterator[tuple[str, Task]]:
    for blocks in BLOCKS:
        for seed in SEEDS:
            domain, problem = blocksworld(blocks, seed=seed)
            yield f"blocksworld {blocks} s{seed}", Task(domain=domain, problem=problem)
    for seed in SEEDS:
        domain, problem = logistics(PACKAGES, seed=seed)
        yield f"logistics {PACKAGES} s{seed}", Task(domain=domain, problem=problem)
    for seed in SEEDS:
        domain, problem = assembly(PARTS, seed=seed)
        yield f"assembly {PARTS} s{seed}", Task(domain=domain, problem=problem)


def scene_of(label: str) -> Path | None:
    """The simulator scene shipped for a domain file, if any."""
    scene = DOMAINS / "scenes" / f"{Path(label.partition(':')[0]).stem}.toml"
    return scene if scene.exists() else None


def measure(label: str, task: Task) -> Row | str:
    """The row of one problem, or why it is left out (`btplan plan` does not solve it)."""
    try:
        plan = btplan.plan(task)
        raw = btplan.plan(task, improve=False)
    except PlanningError as error:
        scene = scene_of(label)
        if scene is not None:
            return (f"{label}: left out, it needs the simulator (scene "
                    f"domains/scenes/{scene.name}); symbolically: {error.reason[:70]}...")
        return f"{label}: left out, `btplan plan` does not solve it: {error.reason}"
    default = Acted.of(btplan.run(task))
    paper = Acted.of(btplan.run(task, config=ActingConfig.paper()))
    return Row(label, len(plan.executed), len(raw.executed), default, paper)


# --- a robot whose skills take ticks -------------------------------------------------------


class Counted:
    """A skill that ends on its `ticks`-th poll (the loop polls once per tick, the start
    included): with success and its effect, or with failure."""

    def __init__(self, ticks: int, effect: Callable[[], None] | None,
                 cancels: list[str], name: str) -> None:
        self.left, self.effect, self.cancels, self.name = ticks, effect, cancels, name

    def poll(self) -> Status:
        self.left -= 1
        if self.left > 0:
            return RUNNING
        if self.effect is None:
            return FAILURE
        self.effect()
        return SUCCESS

    def cancel(self) -> None:
        self.cancels.append(self.name)


class FetchCupRobot(Robot):
    """domains/fetch_cup.bt on a robot: every skill takes `ticks` ticks, and the wall
    button fails after `button_ticks` ticks every time it is pressed."""

    def __init__(self, ticks: int, button_ticks: int) -> None:
        self.room, self.hand, self.door = "dining", "", False
        self.served: set[str] = set()
        self.ticks, self.button_ticks = ticks, button_ticks
        self.cancels: list[str] = []
        """Skills the loop cancelled, as the robot saw it."""
        super().__init__()

    def _skill(self, name: str, effect: Callable[[], None] | None, ticks: int = 0) -> Counted:
        return Counted(ticks or self.ticks, effect, self.cancels, name)

    @condition("at")
    def is_at(self, room: str) -> bool:
        return self.room == room

    @condition("holding")
    def is_holding(self, item: str) -> bool:
        return self.hand == item

    @condition("hand_empty")
    def hand_is_empty(self) -> bool:
        return not self.hand

    @condition("door_open")
    def door_is_open(self) -> bool:
        return self.door

    @condition("delivered")
    def is_delivered(self, item: str) -> bool:
        return item in self.served

    @action("GoTo")
    def go_to(self, room: str) -> Counted:
        return self._skill("GoTo", lambda: setattr(self, "room", room))

    @action("PickKey")
    def pick_key(self, room: str) -> Counted:
        return self._skill("PickKey", lambda: setattr(self, "hand", "key"))

    @action("UnlockDoor")
    def unlock_door(self) -> Counted:
        def unlocked() -> None:
            self.door, self.hand = True, ""

        return self._skill("UnlockDoor", unlocked)

    @action("PressButton")
    def press_button(self) -> Counted:
        return self._skill("PressButton", None, self.button_ticks)

    @action("EnterKitchen")
    def enter_kitchen(self) -> Counted:
        return self._skill("EnterKitchen", lambda: setattr(self, "room", "kitchen"))

    @action("PickCup")
    def pick_cup(self, room: str) -> Counted:
        return self._skill("PickCup", lambda: setattr(self, "hand", "cup"))

    @action("Deliver")
    def deliver(self, room: str) -> Counted:
        def served() -> None:
            self.served.add(self.hand)
            self.hand = ""

        return self._skill("Deliver", served)


# --- printing -----------------------------------------------------------------------------


def acted_cells(a: Acted) -> str:
    return (f"{a.executed:>4} {a.halted:>4} {a.started:>5} {a.observed:>4} {a.ticks:>5} "
            f"{'yes' if a.reached else 'no':>4}")


def print_table(rows: list[Row]) -> None:
    group = "exec halt start  obs ticks  goal"
    print(f"{'':<34} {'plan':>4} {'raw':>4} | {'default (btplan run)':<33} | "
          "paper (Algorithm 1 as published)")
    print(f"{'problem':<34} {'':>4} {'':>4} | {group} | {group}")
    for r in rows:
        print(f"{r.problem:<34} {r.plan:>4} {r.raw:>4} | {acted_cells(r.default)} | "
              f"{acted_cells(r.paper)}")


def print_reasons(rows: list[Row]) -> None:
    for r in rows:
        for preset, a in (("default", r.default), ("paper", r.paper)):
            if not a.reached:
                print(f"  {r.problem}, {preset}: {a.reason[:150]}")


def print_checks(rows: list[Row]) -> None:
    halting = [r.problem for r in rows if r.default.halted]
    longer = [f"{r.problem} ({r.default.executed} > {r.plan})" for r in rows
              if r.default.executed > r.plan]
    longer_raw = [f"{r.problem} ({r.default.executed} > {r.raw})" for r in rows
                  if r.default.executed > r.raw]
    unreached = [r.problem for r in rows if not r.default.reached]
    print(f"every undisturbed default run halts nothing: {'yes' if not halting else 'no'}"
          + (f" ({', '.join(halting)})" if halting else ""))
    print("every undisturbed default run executes at most the plan's actions: "
          + ("yes" if not longer else f"no, {len(longer)} of {len(rows)}: {', '.join(longer)}"))
    print("... at most the plan's actions before plan improvement: "
          + ("yes" if not longer_raw else
             f"no, {len(longer_raw)} of {len(rows)}: {', '.join(longer_raw)}"))
    print("every undisturbed default run reaches the goal: "
          + ("yes" if not unreached else
             f"no, {len(unreached)} of {len(rows)}: {', '.join(unreached)}"))


def slow_skill(task: Task, skill_ticks: list[int], button_ticks: int, max_ticks: int) -> None:
    print(f"{'skill ticks':>11} {'preset':<18} {'ticks':>5} {'goal':>4} {'halted':>6} "
          f"{'cancels':>7} {'failed':>6} {'exec':>4}  executed (* credited by observation)")
    for ticks in skill_ticks:
        for label, config in (("before: paper", ActingConfig.paper()),
                              ("before: algorithm1", ActingConfig.algorithm1()),
                              ("after: default", ActingConfig.default())):
            robot = FetchCupRobot(ticks, button_ticks)
            outcome = btplan.run(task, world=robot, config=config, max_ticks=max_ticks)
            s = outcome.summary()
            observed = list(s.observed)
            shown = []
            for a in outcome.executed:
                name = str(a)
                if name in observed:
                    observed.remove(name)
                    name += "*"
                shown.append(name)
            print(f"{ticks:>11} {label:<18} {outcome.ticks:>5} "
                  f"{'yes' if outcome.reached else 'no':>4} {s.count('halted'):>6} "
                  f"{len(robot.cancels):>7} {s.count('failed'):>6} {len(outcome.executed):>4}  "
                  + ", ".join(shown))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skill-ticks", type=int, nargs="+", default=[1, 2, 3, 5],
                        help="ticks each skill of the robot takes (one row pair each)")
    parser.add_argument("--button-ticks", type=int, default=2,
                        help="ticks after which the wall button fails")
    parser.add_argument("--robot-ticks", type=int, default=200,
                        help="tick limit of the robot's runs")
    args = parser.parse_args()
    started = time.perf_counter()

    rows: list[Row] = []
    notes: list[str] = []
    for label, task in [*shipped(), *generated()]:
        measured = measure(label, task)
        if isinstance(measured, Row):
            rows.append(measured)
        else:
            notes.append(measured)

    print("Undisturbed runs (symbolic world, seed 0, btplan.run's limit of 1000 ticks)")
    print("plan: actions of `btplan plan`; raw: the same before plan improvement;")
    print("exec/halt/start/obs: actions executed, halted, started, and credited by")
    print("observation (their effects held when the tree turned away); goal: reached.")
    print()
    print_table(rows)
    print()
    for note in notes:
        print(note)
    print("not reached:")
    print_reasons(rows)
    print()
    print_checks(rows)
    print()

    fetch = btplan.load(str(DOMAINS / "fetch_cup.bt"))
    print(f"A slow failing skill: fetch_cup.bt on a robot whose skills each take N ticks "
          f"(polls) and whose wall button fails after {args.button_ticks} ticks every time; "
          f"limit {args.robot_ticks} ticks.")
    print("halted: halts in the run's summary; cancels: cancel() calls the robot's skills got.")
    print()
    slow_skill(fetch, args.skill_ticks, args.button_ticks, args.robot_ticks)
    print()
    print(f"took {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
