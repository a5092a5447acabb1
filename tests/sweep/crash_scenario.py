"""A scenario whose first run kills its own worker process, to test that sweeps retry it.

The marker file (BTPLAN_TEST_CRASH_MARKER) makes it happen once: the retried run
finds the marker and goes on as an ordinary `undo` scenario.
"""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

from btplan.model import Task
from btplan.sweep import Scenario
from btplan.worlds.agents import Agent


def _die_once(task: Task, rate: float, seed: int) -> list[Agent]:
    marker = os.environ.get("BTPLAN_TEST_CRASH_MARKER")
    if marker and seed == 1 and not Path(marker).exists():
        Path(marker).write_text("killed\n")
        os.kill(os.getpid(), signal.SIGKILL)
    return []


CRASH_ONCE = Scenario("crash-once", "undo, and the run of seed 1 kills its worker once",
                      ("undo@p={p}",), _die_once)


def _die_always(task: Task, rate: float, seed: int) -> list[Agent]:
    if seed == 1 and os.environ.get("BTPLAN_TEST_CRASH_MARKER"):
        os.kill(os.getpid(), signal.SIGKILL)
    return []


CRASH_ALWAYS = Scenario("crash-always", "the run of seed 1 kills its worker every time",
                        ("undo@p={p}",), _die_always)


def _stall_once(task: Task, rate: float, seed: int) -> list[Agent]:
    marker = os.environ.get("BTPLAN_TEST_CRASH_MARKER")
    if marker and seed == 1 and not Path(marker).exists():
        Path(marker).write_text("stalled\n")
        time.sleep(600)
    return []


STALL_ONCE = Scenario("stall-once", "the run of seed 1 hangs (once)", ("undo@p={p}",),
                      _stall_once)
