"""The library side of Ctrl-C: `stop=` ends a run or a plan at a tick boundary."""

from __future__ import annotations

from pathlib import Path

import pytest

import btplan
from btplan.acting import plan
from btplan.errors import Interrupted

PICK = str(Path(__file__).resolve().parents[2] / "domains" / "pick_place.bt")


def test_a_stopped_run_keeps_its_records_and_halts_the_running_action() -> None:
    task = btplan.load(PICK)
    ticks: list[int] = []
    result = btplan.run(task, stop=lambda: len(ticks) == 5,  # stop before tick 6
                        view=lambda root, statuses, record: ticks.append(record.tick))
    assert result.interrupted and not result.reached and result.reason == "interrupted"
    assert [r.tick for r in result.records] == [1, 2, 3, 4, 5]
    running = [n.name for n in result.records[-1].nodes
               if n.kind == "Action" and n.status.value == "RUNNING"]
    assert running and list(result.halted_on_stop) == running


def test_a_stopped_plan_raises_interrupted_with_its_progress() -> None:
    task = btplan.load(PICK)
    ticks: list[int] = []

    def stop() -> bool:
        ticks.append(1)
        return len(ticks) >= 3

    with pytest.raises(Interrupted) as caught:
        plan(task, stop=stop)
    assert caught.value.progress.startswith("3 expansions and 3 ticks")
