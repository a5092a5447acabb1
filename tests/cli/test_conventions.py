"""What every command shares: version, help that reads like a man page, exit codes."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import btplan.acting.offline
from btplan.cli import app
from btplan.cli.typer_app import EXIT_CODES

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK = str(DOMAINS / "pick_place.bt")
runner = CliRunner()
COMMANDS = [["check"], ["plan"], ["run"], ["export"], ["generate"], ["generate", "blocksworld"],
            ["generate", "gripper"], ["generate", "logistics"]]


def test_version_from_the_app_and_from_python_dash_m() -> None:
    result = runner.invoke(app, ["--version"])
    assert result.exit_code == 0 and re.fullmatch(r"btplan \S+\n", result.stdout)
    module = subprocess.run([sys.executable, "-m", "btplan", "--version"],
                            capture_output=True, text=True, check=False)
    assert module.returncode == 0 and module.stdout == result.stdout


@pytest.mark.parametrize("command", COMMANDS, ids=" ".join)
def test_help_has_no_python_types_and_plain_usage(command: list[str]) -> None:
    result = runner.invoke(app, [*command, "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0
    assert not re.search(r"<(bool|str|int|float|list\[.*?\]|\w+\|[\w|]+)>", result.stdout)
    assert "{" not in result.stdout.split("\n\n")[1] and "[[" not in result.stdout
    if command != ["generate"]:
        assert "Example" in result.stdout


def test_usage_lines_name_what_goes_there() -> None:
    usage = {name: runner.invoke(app, [name, "--help"]).stdout for name in ("plan", "run")}
    assert "Usage: btplan plan [OPTIONS] DOMAIN [PROBLEM]" in usage["plan"]
    assert "Usage: btplan run [OPTIONS] DOMAIN [PROBLEM]" in usage["run"]
    check = runner.invoke(app, ["check", "--help"]).stdout
    assert "Usage: btplan check [OPTIONS] FILE..." in check


def test_the_same_flags_mean_the_same_everywhere(tmp_path: Path) -> None:
    for args in (["plan", PICK, "-q", "-o", str(tmp_path / "a.json")],
                 ["run", PICK, "-q", "--timeout", "60", "--seed", "1"],
                 ["generate", "gripper", "-o", str(tmp_path / "g.pddl"), "--seed", "1"],
                 ["check", "-q", PICK]):
        result = runner.invoke(app, args)
        assert result.exit_code == 0, (args, result.output)
        if args[0] != "run":  # a run's -q keeps its summary: it is the run's report
            assert result.stderr == ""


def test_an_unexpected_exception_is_a_bug_with_exit_3(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(*args: object, **kwargs: object) -> None:
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(btplan.acting.offline, "plan", broken)
    monkeypatch.delenv("BTPLAN_DEBUG", raising=False)
    result = runner.invoke(app, ["plan", PICK])
    assert result.exit_code == 3
    (line,) = result.stderr.strip().splitlines()
    assert "internal error: ZeroDivisionError: division by zero" in line
    assert "bug in btplan" in line and "--debug" in line and "Traceback" not in result.output

    monkeypatch.setenv("BTPLAN_DEBUG", "1")
    result = runner.invoke(app, ["plan", PICK])
    assert result.exit_code == 3 and "Traceback (most recent call last)" in result.stderr


def test_debug_flag_shows_the_traceback(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(*args: object, **kwargs: object) -> None:
        raise KeyError("x")

    monkeypatch.setattr(btplan.acting.offline, "plan", broken)
    monkeypatch.delenv("BTPLAN_DEBUG", raising=False)
    result = runner.invoke(app, ["--debug", "plan", PICK])
    assert result.exit_code == 3 and "Traceback (most recent call last)" in result.stderr


def test_exit_codes_are_one_table() -> None:
    assert sorted(EXIT_CODES) == [0, 1, 2, 3, 130, 143]
    usage = runner.invoke(app, ["plan", PICK, "--no-such-flag"])
    assert usage.exit_code == 2


def test_a_pddl_error_is_explained_in_pddl(tmp_path: Path) -> None:
    domain = tmp_path / "d.pddl"
    domain.write_text(
        "(define (domain d) (:requirements :strips :typing :equality) (:types a b)\n"
        " (:predicates (p ?x - a))\n"
        " (:action act :parameters (?x - a ?y - b) :precondition (p ?x)\n"
        "  :effect (and (not (p ?x)) (= ?x ?y))))\n")
    result = runner.invoke(app, ["check", str(domain)])
    assert result.exit_code == 2
    assert "equalities belong in :precondition" in result.stderr and "where:" not in result.stderr
    domain.write_text(domain.read_text().replace("(= ?x ?y)", "(p ?z)"))
    result = runner.invoke(app, ["check", str(domain)])
    assert "the parameters of act are ?x, ?y" in result.stderr


def test_a_reader_that_stops_early_is_not_an_error() -> None:
    """`btplan generate ... | head -1`: the pipe closes, btplan exits quietly."""
    child = subprocess.Popen(
        [sys.executable, "-m", "btplan", "generate", "blocksworld", "--blocks", "3000"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert child.stdout is not None and child.stdout.readline().startswith(b"(define")
    child.stdout.close()
    _, err = child.communicate(timeout=300)
    assert child.returncode == 0 and err == b""
