"""Every failed run of a sweep gets a cause: no way to the goal in the budget, or its own."""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from btplan.cli import app
from btplan.sweep import explain
from btplan.sweep.output import read_rows
from btplan.sweep.runs import Row

OBSTACLE = str(Path(__file__).resolve().parents[2] / "domains" / "pick_place_obstacle.bt")


def row(method: str, seed: int, success: bool, error: str = "") -> Row:
    return {"scenario": "s", "method": method, "rate": 0.2, "seed": seed,
            "success": success, "error": error, "cause": ""}


def test_the_reference_run_of_the_same_seed_names_the_cause() -> None:
    rows = [row("btplan", 0, False), row("btplan", 1, False), row("repair", 2, False),
            row("repair", 3, True), row("btplan", 4, False, "Timeout")]
    assert explain.needed(rows) == [("replan-unlimited", 0.2, 0), ("replan-unlimited", 0.2, 1),
                                    ("replan-unlimited", 0.2, 2)]
    reference = {(0.2, 0): row("replan-unlimited", 0, False),
                 (0.2, 1): row("replan-unlimited", 1, True)}
    explain.label(rows, reference)
    assert [r["cause"] for r in rows] == [explain.NO_WAY, explain.OWN, explain.UNCHECKED, "", ""]
    assert "| s | btplan | 0.2 | 2 | 1 | 1 | 0 |" in explain.markdown(rows)


def test_a_sweep_writes_the_cause_of_each_failed_run(tmp_path: Path) -> None:
    out = tmp_path / "rows.csv"
    result = CliRunner().invoke(app, ["sweep", OBSTACLE, "--scenario", "obstacle",
                                      "--seeds", "0:2", "--rates", "0", "--method", "btplan",
                                      "--max-ticks", "3", "-j", "1", "-q", "-o", str(out)])
    assert result.exit_code == 0, result.stderr
    rows = read_rows(str(out))
    assert [r["method"] for r in rows] == ["btplan", "btplan"]  # the reruns are not rows
    assert all(not r["success"] and r["cause"] == explain.NO_WAY for r in rows)
    assert rows[0]["reason"] == "the goal was not reached within 3 ticks"
    assert "| obstacle | btplan | 0 | 2 | 2 | 0 | 0 |" in result.stderr
