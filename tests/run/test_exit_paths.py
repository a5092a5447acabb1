"""Every way out of a run halts every running skill (docs/robot.md, "Safe on every way out").

The world below records which skills it has running: started and not yet ended or
halted. After each way out, none is left.
"""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import btplan
from btplan.acting.config import ActingConfig
from btplan.bt import RUNNING, LeafKey, Status
from btplan.errors import WorldError
from btplan.robot import Capabilities
from btplan.worlds.symbolic import SymbolicWorld

ROOT = Path(__file__).resolve().parents[2]
TASK = btplan.load(str(ROOT / "domains" / "pick_place.bt"))


class Tracked(SymbolicWorld):
    """The symbolic world, keeping the set of skills it is running."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]
        self.active: set[LeafKey] = set()
        self.halts: list[LeafKey] = []

    def start(self, key: LeafKey) -> Status:
        return self._track(key, super().start(key))

    def step(self, key: LeafKey) -> Status:
        return self._track(key, super().step(key))

    def halt(self, key: LeafKey) -> None:
        self.halts.append(key)
        self.active.discard(key)
        super().halt(key)

    def _track(self, key: LeafKey, status: Status) -> Status:
        if status is RUNNING:
            self.active.add(key)
        else:
            self.active.discard(key)
        return status


def test_goal_reached_leaves_nothing_running() -> None:
    world = Tracked(TASK)
    outcome = btplan.run(TASK, world=world)
    assert outcome.reached and world.active == set() and outcome.halted_on_stop == ()


def test_the_tick_limit_halts_the_running_skill() -> None:
    world = Tracked(TASK)
    outcome = btplan.run(TASK, world=world, max_ticks=2)  # MoveTo takes 3 ticks
    assert not outcome.reached and world.active == set()
    assert outcome.halted_on_stop == ("MoveTo(cube, tau_cube)",)
    assert world.halts == [("MoveTo", ("cube", "tau_cube"))]


def test_a_stop_request_halts_the_running_skill() -> None:
    world = Tracked(TASK)
    outcome = btplan.run(TASK, world=world, stop=lambda: bool(world.active))
    assert outcome.interrupted and world.active == set()
    assert outcome.halted_on_stop == ("MoveTo(cube, tau_cube)",)


class BrokenFacts(Tracked):
    """A world whose state cannot be read any more after tick 2 (a driver crashed)."""

    reads = 0

    def facts(self) -> frozenset:  # type: ignore[type-arg]
        if self.active:
            self.reads += 1
            if self.reads > 6:
                raise WorldError("the state topic went silent")
        return super().facts()


def test_an_exception_from_the_world_halts_before_it_propagates() -> None:
    world = BrokenFacts(TASK)
    with pytest.raises(WorldError, match="went silent"):
        btplan.run(TASK, world=world)
    assert world.halts and world.active == set()


class CtrlC(Tracked):
    """Ctrl-C arrives while the robot drives (KeyboardInterrupt inside a skill's step)."""

    def step(self, key: LeafKey) -> Status:
        if key[0] == "MoveTo":
            self.active.add(key)
            raise KeyboardInterrupt
        return super().step(key)


def test_keyboard_interrupt_through_the_api_halts_then_propagates() -> None:
    world = CtrlC(TASK)
    with pytest.raises(KeyboardInterrupt):
        btplan.run(TASK, world=world)
    assert ("MoveTo", ("cube", "tau_cube")) in world.halts and world.active == set()


def test_a_skill_error_that_stops_the_run_halts_the_rest() -> None:
    class Raising(Tracked):
        def start(self, key: LeafKey) -> Status:
            if key[0] == "Pick":
                raise RuntimeError("gripper fault")
            return super().start(key)

    world = Raising(TASK)
    outcome = btplan.run(TASK, world=world,
                         config=ActingConfig.default(stop_on_skill_error=True))
    assert not outcome.reached and "gripper fault" in outcome.reason
    assert world.active == set()


def test_a_skill_error_is_that_actions_failure_and_the_run_goes_on() -> None:
    class Slips(Tracked):
        slipped = False

        def start(self, key: LeafKey) -> Status:
            if key[0] == "Pick" and not self.slipped:
                self.slipped = True
                raise RuntimeError("the cube slipped")
            return super().start(key)

    outcome = btplan.run(TASK, world=Slips(TASK))
    assert outcome.reached
    errors = [e for r in outcome.records for e in r.errors]
    assert errors == [("Pick(cube)", "the cube slipped")]
    assert "Pick(cube)" in outcome.summary().failed
    line = next(r for r in outcome.records if r.errors).to_dict()
    assert line["errors"] == [{"action": "Pick(cube)", "message": "the cube slipped"}]


class Stubborn(SymbolicWorld):
    """A skill that reports when it has stopped, and never does."""

    capabilities = Capabilities(refines=True, reports_stopped=True)

    def stopped(self, key: LeafKey) -> bool:
        return key[0] != "MoveTo"


def test_a_skill_that_does_not_stop_is_named() -> None:
    outcome = btplan.run(TASK, world=Stubborn(TASK), max_ticks=2,
                         config=ActingConfig.default(halt_wait=0.05),
                         clock=btplan.acting.FakeClock())
    assert outcome.unstopped == ["MoveTo(cube, tau_cube)"]


SIGTERM_SCRIPT = textwrap.dedent("""
    import os, signal, sys
    import btplan
    from btplan.worlds.symbolic import SymbolicWorld

    class World(SymbolicWorld):
        ticks = 0
        def step(self, key):
            self.ticks += 1
            if self.ticks == 2:
                os.kill(os.getpid(), signal.SIGTERM)
            return super().step(key)
        def halt(self, key):
            print("halt", key[0], flush=True)
            super().halt(key)

    task = btplan.load(sys.argv[1])
    btplan.run(task, world=World(task))
    print("not reached: the run should have ended", flush=True)
""")


def test_sigterm_through_the_api_halts_then_exits_143(tmp_path: Path) -> None:
    script = tmp_path / "term.py"
    script.write_text(SIGTERM_SCRIPT)
    done = subprocess.run([sys.executable, str(script), str(ROOT / "domains" / "pick_place.bt")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 128 + signal.SIGTERM, done.stderr
    assert done.stdout.splitlines() == ["halt MoveTo"]
