"""`btplan generate`: classic problems on stdout or in a file, as PDDL or .bt."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.cli import app
from btplan.lang import load

runner = CliRunner()


@pytest.mark.parametrize(
    ("args", "objects"),
    [
        (["blocksworld", "--blocks", "8", "--seed", "3"], 8),
        (["gripper", "--balls", "5", "--rooms", "3"], 3 + 5 + 2),
        (["logistics", "--packages", "4", "--cities", "3", "--locations", "2"], 3 + 6 + 3 + 1 + 4),
        (["assembly", "--parts", "7", "--seed", "2"], 2 + 3 + 1 + 7),
    ],
)
@pytest.mark.parametrize("fmt", ["pddl", "bt"])
def test_output_loads_back(tmp_path: Path, args: list[str], objects: int, fmt: str) -> None:
    result = runner.invoke(app, ["generate", *args, "--format", fmt])
    assert result.exit_code == 0, result.output
    path = tmp_path / f"both.{fmt}"
    path.write_text(result.stdout)
    task = load([str(path)])
    assert task.domain.name == args[0]
    assert len(task.problem.objects) == objects


def test_same_seed_same_bytes() -> None:
    args = ["generate", "logistics", "--packages", "6", "--seed", "11"]
    assert runner.invoke(app, args).stdout == runner.invoke(app, args).stdout


def test_domain_only_and_problem_only(tmp_path: Path) -> None:
    domain = runner.invoke(app, ["generate", "blocksworld", "--domain-only"]).stdout
    problem = runner.invoke(app, ["generate", "blocksworld", "--problem-only"]).stdout
    assert domain.startswith("(define (domain blocksworld)") and "problem" not in domain
    assert problem.startswith("(define (problem blocksworld_5_s0)")


def test_output_file_is_written(tmp_path: Path) -> None:
    out = tmp_path / "bw.bt"
    result = runner.invoke(app, ["generate", "blocksworld", "--format", "bt", "-o", str(out)])
    assert result.exit_code == 0 and result.stdout == ""
    assert load([str(out)]).problem.name == "blocksworld_5_s0"


@pytest.mark.parametrize(
    "args",
    [
        ["blocksworld", "--blocks", "0"],
        ["gripper", "--rooms", "1"],
        ["blocksworld", "--domain-only", "--problem-only"],
    ],
)
def test_bad_sizes_exit_2(args: list[str]) -> None:
    result = runner.invoke(app, ["generate", *args])
    assert result.exit_code == 2
    assert "error:" in result.stderr
