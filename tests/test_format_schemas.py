"""The JSON Schemas the reference pages show hold for what btplan writes.

Trace lines are plain dictionaries, so their schema (docs/reference/trace.schema.json)
is written by hand; real runs' traces are checked against it, every field it names must
be written by some run, and every field must be explained on docs/reference/trace.md,
so that neither the schema nor the page can fall behind the writer. Saved trees have
pydantic models and the page shows the schema generated from them; here real saved
trees of shipped domains are checked against that schema, which is the contract a
reader of the files relies on.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from jsonschema import Draft202012Validator

from btplan.acting.records import ExpansionNote, TickRecord
from btplan.bt.formats.saved import SavedTree
from btplan.bt.status import Status
from btplan.bt.trace import NodeTick
from btplan.monitor.run_monitor import TickUpdate
from btplan.worlds.agents import Disturbance

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "docs" / "reference"
TRACE_SCHEMA: dict[str, Any] = json.loads((REFERENCE / "trace.schema.json").read_text())

RUNS = {
    "example2": ["domains/pick_place_obstacle.bt", "--scenario", "examples/example2.dist"],
    "example2-paper": ["domains/pick_place_obstacle.bt", "--scenario",
                       "examples/example2_paper.dist", "--paper"],
    "failed-action": ["domains/pick_place.bt", "--disturb", "fail:Pick@2"],
    "observed-action": ["domains/pick_place.bt", "--disturb", "help:MoveTo@2"],
    "goal-lost": ["domains/pick_place.bt", "--keep", "--max-ticks", "20", "--disturb",
                  "undo@12"],
}
"""Runs whose traces between them write every field a trace line can hold, but `errors`
(a world that raises; checked from the writer below)."""

SAVED = ["pick_place", "pick_place_obstacle", "blocksworld", "gripper", "planner_sussman",
         "run_alternatives"]
"""Shipped domains whose planned trees are checked against the saved trees' schema."""


def btplan(*arguments: str, cwd: Path) -> None:
    done = subprocess.run([sys.executable, "-m", "btplan", *arguments], cwd=cwd,
                          env=dict(os.environ), capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]


def trace_of(run: str, tmp_path: Path) -> list[dict[str, Any]]:
    out = tmp_path / f"{run}.jsonl"
    btplan("run", *RUNS[run], "-q", "--trace", str(out), cwd=ROOT)
    return [json.loads(line) for line in out.read_text().splitlines()]


def problems(validator: Draft202012Validator, value: Any) -> list[str]:
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message}"
            for e in validator.iter_errors(value)]


def test_the_trace_schema_is_a_schema() -> None:
    Draft202012Validator.check_schema(TRACE_SCHEMA)


@pytest.fixture(scope="module")
def traces(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict[str, Any]]]:
    folder = tmp_path_factory.mktemp("traces")
    return {run: trace_of(run, folder) for run in RUNS}


@pytest.mark.parametrize("run", RUNS)
def test_every_line_of_a_real_trace_fits_the_schema(
        run: str, traces: dict[str, list[dict[str, Any]]]) -> None:
    validator = Draft202012Validator(TRACE_SCHEMA)
    lines = traces[run]
    assert lines, "the run wrote no trace"
    for line in lines:
        assert not problems(validator, line), (line["tick"], problems(validator, line))
    assert [line["tick"] for line in lines] == list(range(1, len(lines) + 1))
    assert "facts_at_start" in lines[0] and "tree" in lines[0]
    assert not any("facts_at_start" in line for line in lines[1:])


def test_a_line_with_every_field_fits_the_schema() -> None:
    """The writer itself, with every field filled, `errors` among them."""
    record = TickRecord(
        tick=3, status="FAILURE",
        nodes=(NodeTick("n0", "Action", "Pick(cube)", Status.FAILURE),),
        started=("Pick(cube)",), halted=("MoveTo(goal, tau_goal)",),
        finished=("MoveTo(cube, tau_cube)",), failed=("Pick(cube)",),
        disturbances=(Disturbance(3, "undo@3", "undid MoveTo(cube, tau_cube)", "undo"),),
        expansions=(ExpansionNote("near(cube)", ("MoveTo(cube, tau_cube)",), 1, 2),),
        added=("near(cube)",), removed=("near(goal)",), observed=("MoveTo(cube, tau_cube)",),
        errors=(("Pick(cube)", "the gripper did not answer"),), goal="lost")
    update = TickUpdate(record, [], [(1, "FAILURE")], [(1, 0, "Action", "Pick(cube)")],
                        ["hand_empty()"])
    line = json.loads(update.line)
    assert set(line) == set(TRACE_SCHEMA["properties"])
    assert not problems(Draft202012Validator(TRACE_SCHEMA), line)


def test_the_runs_write_every_field_the_schema_names(
        traces: dict[str, list[dict[str, Any]]]) -> None:
    written = {key for lines in traces.values() for line in lines for key in line}
    assert written | {"errors"} == set(TRACE_SCHEMA["properties"])


def test_the_trace_page_explains_every_field() -> None:
    page = (REFERENCE / "trace.md").read_text()
    for name in TRACE_SCHEMA["properties"]:
        assert f"| `{name}` |" in page, f"trace.md does not explain {name}"
    assert "<!-- schema trace.schema.json -->" in page


@pytest.mark.parametrize("domain", SAVED)
def test_saved_trees_fit_the_tree_schema(domain: str, tmp_path: Path) -> None:
    out = tmp_path / "tree.json"
    btplan("plan", f"domains/{domain}.bt", "-q", "-o", str(out), cwd=ROOT)
    validator = Draft202012Validator(SavedTree.model_json_schema())
    tree = json.loads(out.read_text())
    assert not problems(validator, tree)


def test_the_tree_page_explains_every_field() -> None:
    page = (REFERENCE / "tree-json.md").read_text()
    node = SavedTree.model_json_schema()["$defs"]["SavedNode"]["properties"]
    for name in [*SavedTree.model_fields, *node]:
        assert f"| `{name}` |" in page, f"tree-json.md does not explain {name}"
