"""The robot API through `btplan.run`: binding, skills of every kind, errors, refiners, --world.

Every run paces on a FakeClock and every skill ends after a number of polls (or when the
test completes its Future), so no test sleeps or depends on how fast the machine is.
"""

from __future__ import annotations

import subprocess
import sys
from collections.abc import Callable
from concurrent.futures import Future
from pathlib import Path
from threading import Event
from typing import Any

import pytest
from typer.testing import CliRunner

import btplan
from btplan.acting import ActingConfig, FakeClock
from btplan.bt import RUNNING, SUCCESS, LeafKey, Status
from btplan.cli import app
from btplan.errors import InputError, WorldError
from btplan.model import Atom
from btplan.robot import Ask, Robot, action, condition

ROOT = Path(__file__).resolve().parents[2]
PICK_PLACE = str(ROOT / "domains" / "pick_place.bt")
TASK = btplan.load(PICK_PLACE)
PLAN = ["MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]
runner = CliRunner()


class Arm:
    """The state of a test robot for pick_place, and what each action does to it."""

    def __init__(self) -> None:
        self.near: str | None = None
        self.held: str | None = None
        self.cube: str | None = None

    def effect(self, name: str, args: tuple[str, ...]) -> Callable[[], None]:
        def move() -> None:
            self.near = args[0]

        def pick() -> None:
            self.held = args[0]

        def place() -> None:
            self.held, self.cube = None, args[1]

        return {"MoveTo": move, "Pick": pick, "Place": place}[name]


def conditions(robot: Robot, arm: Arm) -> Robot:
    """The four changing predicates of pick_place over `arm`."""
    robot.condition("on")(lambda o, l: arm.cube == l)
    robot.condition("holding")(lambda o: arm.held == o)
    robot.condition("hand_empty")(lambda: arm.held is None)
    robot.condition("near")(lambda l: arm.near == l or (l == arm.held))
    return robot


class Steps:
    """A skill that is done at its `polls`-th poll: it then changes the arm and succeeds."""

    def __init__(self, polls: int, done: Callable[[], None], log: list[str],
                 comes_to_rest: bool = True) -> None:
        self.left, self.done, self.log, self.rest = polls, done, log, comes_to_rest

    def poll(self) -> Status | None:
        self.left -= 1
        if self.left > 0:
            return None  # None is RUNNING
        self.done()
        return SUCCESS

    def cancel(self) -> None:
        self.log.append("cancel")

    def stopped(self) -> bool:
        return self.rest


def stepping_robot(arm: Arm, polls: int = 3, log: list[str] | None = None,
                   comes_to_rest: bool = True) -> Robot:
    """A robot whose every action returns a Steps skill."""
    robot = conditions(Robot(), arm)
    for name in ("MoveTo", "Pick", "Place"):
        def start(*args: str, name: str = name) -> Steps:
            return Steps(polls, arm.effect(name, args), log if log is not None else [],
                         comes_to_rest)

        robot.action(name)(start)
    return robot


def act(robot: Any, **options: Any) -> btplan.RunOutcome:
    return btplan.run(TASK, world=robot, rate=10, clock=FakeClock(), **options)


# --- bind ----------------------------------------------------------------------------


def test_bind_names_each_missing_action_and_changing_predicate_with_a_close_match() -> None:
    robot = Robot()
    robot.condition("holding")(lambda o: False)
    robot.condition("nears")(lambda l: False)
    robot.action("Pickup")(lambda o: True)
    with pytest.raises(InputError) as caught:
        act(robot)
    message = str(caught.value)
    assert "Robot does not fit domain 'pick_place'" in message
    assert "'Pickup' is no action of the domain (did you mean 'Pick'?)" in message
    assert "no action for MoveTo, Place" in message
    assert "'nears' is no predicate of the domain (did you mean 'near'?)" in message
    assert "no condition for hand_empty, on" in message
    assert "see docs/robot.md" in message


def test_unknown_names_and_functions_that_cannot_take_their_arguments_are_refused() -> None:
    class Clumsy(Robot):
        @condition("on")
        def on(self, o: str) -> bool:  # on(o, l) has two arguments
            return False

        @condition("grasped")
        def grasped(self, o: str) -> bool:
            return False

        @action("Pick", threaded=True)
        def pick(self, o: str) -> bool:  # a threaded action also takes `stop`
            return True

    robot = Clumsy()
    robot.refiner("Fly", "t")(lambda ask: [])
    robot.refiner("MoveTo", "l")(lambda ask: [])
    with pytest.raises(InputError) as caught:
        robot.bind(TASK)
    error = caught.value
    assert "'grasped' is no predicate of the domain" in error.message
    assert "a refiner: 'Fly' is no action of the domain" in error.message
    assert "a refiner is bound for MoveTo.l, but MoveTo refines t" in error.message
    assert "Clumsy.pick(o) cannot take Pick(o, stop)" in error.message
    assert "Clumsy.on(o) cannot take on(o, l)" in error.message
    # The error points at the class to fix.
    assert error.span is not None and error.span.path.endswith("test_robot_api.py")
    assert (error.source_line or "").strip() == "class Clumsy(Robot):"


def test_static_predicates_come_from_the_problem() -> None:
    arm = Arm()
    robot = stepping_robot(arm, polls=1)
    robot.bind(TASK)
    assert robot.check(("free", ("tau_goal",)))
    assert robot.check(("route", ("cube", "tau_cube")))
    assert not robot.check(("route", ("goal", "tau_cube")))
    assert robot.check(("route", ("_", "tau_goal")))  # a wildcard matches any object
    assert Atom("route", ("goal", "tau_goal")) in robot.facts()
    assert act(robot).reached


def test_a_condition_the_robot_binds_answers_even_for_a_static_predicate() -> None:
    arm = Arm()
    robot = stepping_robot(arm, polls=1)
    robot.condition("free")(lambda t: t != "tau_goal")  # something stands on the way
    robot.bind(TASK)
    assert robot.check(("free", ("tau_cube",))) and not robot.check(("free", ("tau_goal",)))
    outcome = act(robot, max_ticks=20)
    assert not outcome.reached
    assert [str(a) for a in outcome.executed] == PLAN[:2]


def test_a_condition_that_raises_in_facts_is_named() -> None:
    arm = Arm()
    robot = stepping_robot(arm)
    robot.condition("hand_empty")(lambda: 1 / 0)
    with pytest.raises(WorldError, match=r"the condition hand_empty\(\) raised "
                                         r"ZeroDivisionError: division by zero"):
        act(robot)


class TupleWorld:
    """A world written against the contract alone, whose facts are plain tuples."""

    def __init__(self) -> None:
        self.arm = Arm()
        self.left: dict[LeafKey, int] = {}

    def facts(self) -> list[tuple[str, ...]]:
        arm = self.arm
        out = [("free", "tau_cube"), ("free", "tau_goal"), ("route", "cube", "tau_cube"),
               ("route", "goal", "tau_goal")]
        out += [("near", arm.near)] if arm.near else []
        out += [("holding", arm.held)] if arm.held else [("hand_empty",)]
        out += [("on", "cube", arm.cube)] if arm.cube else []
        return out

    def check(self, key: LeafKey) -> bool:
        return (key[0], *key[1]) in self.facts()

    def start(self, key: LeafKey) -> Status:
        self.left[key] = 2
        return self.step(key)

    def step(self, key: LeafKey) -> Status:
        self.left[key] -= 1
        if self.left[key]:
            return RUNNING
        self.arm.effect(key[0], key[1])()
        return SUCCESS

    def halt(self, key: LeafKey) -> None:
        self.left.pop(key, None)


def test_facts_as_plain_tuples_are_read_as_atoms() -> None:
    outcome = act(TupleWorld())
    assert outcome.reached
    assert [str(a) for a in outcome.executed] == PLAN


# --- skills ----------------------------------------------------------------------------


def test_a_skill_object_is_polled_once_per_tick_until_it_succeeds() -> None:
    arm = Arm()
    outcome = act(stepping_robot(arm, polls=3))
    assert outcome.reached and [str(a) for a in outcome.executed] == PLAN
    started = [(r.tick, list(r.started)) for r in outcome.records if r.started]
    # Each skill is polled at its start and once in each later tick: it succeeds in its
    # third tick, and the tree starts the next one in that same tick.
    assert started == [(1, PLAN[:1]), (3, PLAN[1:2]), (5, PLAN[2:3]), (7, PLAN[3:])]
    assert outcome.ticks == 9
    assert outcome.summary().halted == [] and outcome.summary().failed == []


def test_a_skill_cut_short_is_cancelled_and_waited_for() -> None:
    arm, log = Arm(), list[str]()
    outcome = act(stepping_robot(arm, polls=5, log=log), max_ticks=3)
    assert not outcome.reached
    assert outcome.halted_on_stop == ("MoveTo(cube, tau_cube)",)
    assert log == ["cancel"] and outcome.unstopped == []


def test_a_skill_that_does_not_come_to_rest_is_named() -> None:
    arm, log = Arm(), list[str]()
    clock = FakeClock()
    robot = stepping_robot(arm, polls=5, log=log, comes_to_rest=False)
    outcome = btplan.run(TASK, world=robot, rate=10, clock=clock, max_ticks=3,
                         config=ActingConfig.default(halt_wait=0.5))
    assert outcome.unstopped == ["MoveTo(cube, tau_cube)"]
    assert outcome.summary().unstopped == ["MoveTo(cube, tau_cube)"]
    assert clock.now() >= 0.69  # three ticks at 10 Hz (0, 0.1, 0.2), then the whole wait


class Driver:
    """A robot's driver that answers with Futures; the test completes them (as an agent,
    before a tick) two ticks after they were asked for."""

    name = "driver"

    def __init__(self, arm: Arm) -> None:
        self.arm = arm
        self.pending: list[tuple[int, Future[bool], Callable[[], None]]] = []
        self.tick = 0

    def call(self, name: str, *args: str) -> Future[bool]:
        future: Future[bool] = Future()
        self.pending.append((self.tick + 2, future, self.arm.effect(name, args)))
        return future

    def act(self, world: Any, tick: int) -> list[Any]:
        self.tick = tick
        for due, future, effect in [p for p in self.pending if p[0] <= tick]:
            self.pending.remove((due, future, effect))
            if not future.cancelled():
                effect()
                future.set_result(True)
        return []


def test_an_action_returning_a_future_runs_until_the_future_is_done() -> None:
    arm = Arm()
    driver = Driver(arm)
    robot = conditions(Robot(), arm)
    robot.action("MoveTo")(lambda l, t: driver.call("MoveTo", l, t))
    robot.action("Pick")(lambda o: driver.call("Pick", o))
    robot.action("Place")(lambda o, l: driver.call("Place", o, l))
    outcome = act(robot, agents=[driver])
    assert outcome.reached and [str(a) for a in outcome.executed] == PLAN
    # The driver does the work before the tick: the tree sees the effect first.
    assert outcome.summary().observed == PLAN


def test_a_threaded_action_gets_its_arguments_and_a_stop_event() -> None:
    arm, seen = Arm(), []

    class Threaded(Robot):
        """Threaded skills that end at once: the loop polls their Futures until done."""

        @condition("on")
        def on(self, o: str, l: str) -> bool:
            return arm.cube == l

        @condition("holding")
        def holding(self, o: str) -> bool:
            return arm.held == o

        @condition("hand_empty")
        def hand_empty(self) -> bool:
            return arm.held is None

        @condition("near")
        def near(self, l: str) -> bool:
            return arm.near == l or arm.held == l

        def work(self, name: str, args: tuple[str, ...], stop: Event) -> bool:
            seen.append((name, args, isinstance(stop, Event) and not stop.is_set()))
            arm.effect(name, args)()
            return True

        @action("MoveTo", threaded=True)
        def move(self, l: str, t: str, stop: Event) -> bool:
            return self.work("MoveTo", (l, t), stop)

        @action("Pick", threaded=True)
        def pick(self, o: str, stop: Event) -> bool:
            return self.work("Pick", (o,), stop)

        @action("Place", threaded=True)
        def place(self, o: str, l: str, stop: Event) -> bool:
            return self.work("Place", (o, l), stop)

    robot = Threaded()
    # The loop never waits for a thread: it ticks (on the fake clock) until each is done.
    outcome = act(robot, max_ticks=10**6)
    robot.close()
    assert outcome.reached and [str(a) for a in outcome.executed] == PLAN
    assert seen == [("MoveTo", ("cube", "tau_cube"), True), ("Pick", ("cube",), True),
                    ("MoveTo", ("goal", "tau_goal"), True), ("Place", ("cube", "goal"), True)]


def pick_raises(times: int) -> tuple[Robot, Arm]:
    """A robot whose Pick raises the first `times` times."""
    arm = Arm()
    robot = stepping_robot(arm, polls=1)
    raised: list[int] = []

    def pick(o: str) -> bool:
        if len(raised) < times:
            raised.append(1)
            raise RuntimeError("the gripper reports a fault")
        arm.held = o
        return True

    robot.action("Pick")(pick)
    return robot, arm


def test_a_skill_that_raises_fails_with_its_message_and_the_run_goes_on() -> None:
    robot, _ = pick_raises(1)
    outcome = act(robot)
    assert outcome.reached
    failing = [r for r in outcome.records if r.errors]
    assert len(failing) == 1
    assert failing[0].errors == (("Pick(cube)", "the gripper reports a fault"),)
    assert failing[0].failed == ("Pick(cube)",)
    assert outcome.summary().errors == [("Pick(cube)", "the gripper reports a fault")]
    assert [str(a) for a in outcome.executed] == PLAN


def test_stop_on_skill_error_ends_the_run_with_the_skill_s_message() -> None:
    robot, _ = pick_raises(1)
    outcome = act(robot, config=ActingConfig.default(stop_on_skill_error=True))
    assert not outcome.reached
    assert outcome.reason == "Pick(cube) raised: the gripper reports a fault"
    assert outcome.records[-1].errors == (("Pick(cube)", "the gripper reports a fault"),)


def test_a_refiner_gets_an_ask_with_the_where_constraints() -> None:
    arm = Arm()
    robot = stepping_robot(arm, polls=1)
    asks: list[Ask] = []

    @robot.refiner("MoveTo", "t")
    def trajectory(ask: Ask) -> list[str]:
        asks.append(ask)
        return [f"tau_{ask.binding['l']}"]

    outcome = act(robot)
    assert outcome.reached and [str(a) for a in outcome.executed] == PLAN
    assert {(a.action, a.parameter, a.type) for a in asks} == {("MoveTo", "t", "trajectory")}
    assert {a.where for a in asks} == {(("route", ("cube", "?t")),),
                                       (("route", ("goal", "?t")),)}


def test_an_ask_keeps_negated_constraints_and_equalities(tmp_path: Path) -> None:
    domain = tmp_path / "shelf.bt"
    domain.write_text("""
domain shelf {
    types { place }
    constants { floor : place }
    predicates {
        blocked(p: place)
        stored
    }
    action Store(p: place refined) {
        where: p != floor, not blocked(p)
        post: stored
    }
}
problem store_it for shelf {
    objects { top, bottom : place }
    init { blocked(bottom) }
    goal { stored }
}
""")
    stored: list[str] = []
    asks: list[Ask] = []
    robot = Robot()
    robot.condition("stored")(lambda: bool(stored))
    robot.action("Store")(stored.append)  # answers None: done at once

    @robot.refiner("Store", "p")
    def shelf(ask: Ask) -> list[str]:
        asks.append(ask)
        return ["top"]

    outcome = btplan.run(btplan.load(str(domain)), world=robot, clock=FakeClock(), rate=10)
    assert outcome.reached and stored == ["top"]
    assert asks[0].where == (("!=", ("?p", "floor")), ("not blocked", ("?p",)))


# --- the example and --world ---------------------------------------------------------


def test_the_example_robot_fits_its_domain() -> None:
    sys.path.insert(0, str(ROOT / "examples"))
    try:
        from my_robot import FetchRobot  # type: ignore[import-not-found]
    finally:
        sys.path.remove(str(ROOT / "examples"))
    robot = FetchRobot(seed=3, fail=0.5)
    robot.bind(TASK)
    assert robot.facts() == TASK.initial_state


def test_the_example_robot_reaches_the_goal_from_the_command_line() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "btplan", "run", PICK_PLACE, "--world",
         str(ROOT / "examples" / "my_robot.py") + ":FetchRobot", "--hz", "50", "-q"],
        capture_output=True, text=True, check=False, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert "goal reached" in done.stderr
    assert "Place(cube, goal)" in done.stderr


def world_error(*args: str) -> str:
    result = runner.invoke(app, ["run", PICK_PLACE, "--world", *args])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: --world:1:1: "), lines
    return lines[0]


def test_world_errors_give_exit_2_and_one_clean_line(tmp_path: Path) -> None:
    robot = tmp_path / "robot.py"
    robot.write_text("class FetchRobot:\n    def check(self, key):\n        return False\n\n"
                     "class Broken:\n    def __init__(self):\n        raise OSError('no arm')\n")
    assert world_error(f"{tmp_path / 'none.py'}:FetchRobot").endswith(
        f"no such file: {tmp_path / 'none.py'}")
    assert world_error(f"{robot}:FetchRobt").endswith(
        f"{robot} has no class or function named 'FetchRobt' (did you mean 'FetchRobot'?)")
    assert world_error(f"{robot}:FetchRobot").endswith(
        "which lacks start, step, halt, facts of the world contract (see docs/robot.md)")
    assert world_error(f"{robot}:Broken").endswith(
        "raised while starting: OSError: no arm")
    assert world_error(str(robot)).endswith("expected FILE.py:CLASS or MODULE:CLASS, "
                                            f"got '{robot}'")
    assert world_error("no_such_package.robot:FetchRobot").endswith(
        "cannot import no_such_package.robot: ModuleNotFoundError: "
        "No module named 'no_such_package'")


def test_a_robot_that_does_not_fit_points_at_its_class(tmp_path: Path) -> None:
    robot = tmp_path / "robot.py"
    robot.write_text("from btplan.robot import Robot, action\n\n\n"
                     "class Half(Robot):\n    @action('Pickup')\n"
                     "    def pick(self, o):\n        return True\n")
    result = runner.invoke(app, ["run", PICK_PLACE, "--world", f"{robot}:Half"])
    assert result.exit_code == 2 and "Traceback" not in result.output
    first, line, caret = result.stderr.strip().splitlines()[:3]
    assert first.startswith(f"error: {robot}:4:1: Half does not fit domain 'pick_place': "
                            "'Pickup' is no action of the domain (did you mean 'Pick'?)")
    assert line.strip() == "class Half(Robot):" and caret.strip() == "^"
