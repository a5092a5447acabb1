"""The lean start of `btplan plan` answers exactly as the typer command does.

Each argument vector runs twice in fresh interpreters: through the console script
(`main`, which takes the lean path when it can read the arguments) and through the
typer app alone. Standard output, standard error (run times masked), the exit code
and every file written (read, then removed for the next run) must be the same.
"""

from __future__ import annotations

import itertools
import re
import subprocess
import sys
from pathlib import Path

import pytest

from btplan.cli.lean import _decimal, _integer, read_plan_arguments
from btplan.lang.generators import generate

SCRIPT = "from btplan.cli import main; import sys; sys.argv[0] = 'btplan'; main()"
TYPER = ("import sys; from btplan.cli import app, only_the_command_asked_for; "
         "only_the_command_asked_for(sys.argv[1:2]); app(prog_name='btplan')")
SECONDS = re.compile(r"\d+\.\d+ s\b")


def run(script: str, argv: list[str], where: Path) -> tuple[int, str, str, dict[str, str]]:
    done = subprocess.run([sys.executable, "-c", script, *argv], capture_output=True,
                          text=True, timeout=300, cwd=where)
    written = {}
    for path in sorted(where.iterdir()):
        if path.suffix != ".pddl":
            written[path.name] = path.read_text()
            path.unlink()
    return done.returncode, done.stdout, SECONDS.sub("T s", done.stderr), written


@pytest.fixture()
def problem(tmp_path: Path) -> Path:
    domain_text, problem_text = generate("blocksworld", "pddl", seed=2, blocks=3)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    return tmp_path


VECTORS = [
    ["plan", "d.pddl", "p.pddl"],
    ["plan", "d.pddl", "p.pddl", "-f", "dot", "-o", "tree.dot", "--plan-out", "plan.txt"],
    ["plan", "-q", "d.pddl", "--format=xml", "p.pddl", "--seed", "3", "--timeout=2.5"],
    ["plan", "d.pddl", "p.pddl", "--out", "t.json", "-o", "u.json", "--paper", "--no-search"],
    ["plan", "d.pddl", "p.pddl", "--no-improve", "--plan-out", "plan.txt"],
    ["plan", "d.pddl", "p.pddl", "--goal", "(and (on b1 b3) (clear b1))", "--plan-out", "-"],
    ["plan", "d.pddl", "p.pddl", "--goal=(on b1 b4)"],
    ["plan", "d.pddl", "p.pddl", "--max-expansions", "0"],
    ["plan", "d.pddl", "p.pddl", "--max-alternatives", "1", "--max-ticks", "3"],
    ["plan", "missing.pddl", "p.pddl"],
    ["plan", "p.pddl", "d.pddl"],
    ["plan", "d.pddl", "p.pddl", "--plan-out", "no/such/folder/plan.txt"],
    ["plan", "d.pddl", "p.pddl", "-f", "yaml"],
    ["plan", "d.pddl", "p.pddl", "--timeout", "-1"],
    ["plan", "d.pddl", "p.pddl", "extra"],
    ["plan"],
]


@pytest.mark.parametrize("argv", VECTORS, ids=[" ".join(v[1:]) or "none" for v in VECTORS])
def test_the_lean_start_and_the_typer_app_answer_alike(argv: list[str], problem: Path) -> None:
    assert run(SCRIPT, argv, problem) == run(TYPER, argv, problem)


def test_the_lean_start_reads_plain_arguments() -> None:
    assert read_plan_arguments(["d", "p", "-o", "-", "--seed", "7", "--timeout=1.5", "-q"]) == {
        "domain": "d", "problem": "p", "out": "-", "seed": 7, "timeout": 1.5, "quiet": True}
    assert read_plan_arguments(["-", "--out", "a", "-o", "b"]) == {
        "domain": "-", "problem": None, "out": "a"}


@pytest.mark.parametrize("args", [
    [], ["--help"], ["d", "-h"], ["d", "--seed", "x"], ["d", "--seed", "-1"], ["d", "-o=x"],
    ["d", "--timeout", "1e3"], ["d", "-f", "XML"], ["d", "p", "q"], ["d", "--"], ["d", "-qo", "x"],
    ["d", "--plan-out"], ["d", "--paper=1"], ["d", "--format="], ["d", "--unknown"],
])
def test_anything_else_is_left_to_typer(args: list[str]) -> None:
    assert read_plan_arguments(args) is None


def test_the_vectors_above_take_both_paths() -> None:
    lean = [read_plan_arguments(argv[1:]) is not None for argv in VECTORS]
    assert lean == [True] * 12 + [False] * 4


def test_plain_numbers_are_what_the_patterns_accept() -> None:
    """Integers `[0-9]{1,18}` and decimals `[0-9]{1,15}(\\.[0-9]{0,6})?|\\.[0-9]{1,6}`,
    read without compiling those patterns: every short word of digits, points, signs,
    letters and non-ASCII digits, and the lengths at the edges."""
    integer = re.compile(r"[0-9]{1,18}")
    decimal = re.compile(r"[0-9]{1,15}(\.[0-9]{0,6})?|\.[0-9]{1,6}")
    words = ["".join(w) for k in range(5) for w in itertools.product("01.a-\u00b2\u0663 ", repeat=k)]
    words += ["1" * 18, "1" * 19, "1" * 15 + ".123456", "1" * 16, ".123456", ".1234567",
              "1.1234567", "1" * 15 + ".", "1" * 16 + ".5"]
    for word in words:
        assert (_integer(word), _decimal(word)) == (
            bool(integer.fullmatch(word)), bool(decimal.fullmatch(word))), word
