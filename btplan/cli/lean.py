"""The lean start of `btplan plan`: plain arguments read without building the typer app.

Importing typer (and click beneath it) and building the command costs about 0.1 s of
CPU, more than a small competition problem takes to plan, and a command-line planner
is measured as a whole process. So the console script reads the common forms of
`btplan plan ...` itself and runs the same code the typer command runs
(`cli/planning.py`). It accepts only what it is sure to read as the typer command
does: the options of `btplan plan --help` as separate words or `--name=value`, values
that are plain words, plain integers and plain decimals, at most two positional
arguments. Anything else (help, an unknown or malformed option, a missing argument, a
value typer would have to convert or refuse) returns None, and the typer app runs and
answers exactly as it always does. `tests/cli/test_lean.py` checks both ways give the
same outputs and exit codes.
"""

from __future__ import annotations

import os
import sys

from btplan.cli.planning import FORMATS

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, NoReturn

_VALUED = {
    "-f": "fmt", "--format": "fmt", "-o": "out", "--output": "out", "--out": "out_alias",
    "--plan-out": "plan_out", "--trace-expansions": "trace_expansions", "--seed": "seed",
    "--max-expansions": "max_expansions", "--max-ticks": "max_ticks",
    "--max-alternatives": "max_alternatives", "--timeout": "timeout",
    "--max-memory": "max_memory", "--goal": "goal",
}
_FLAGS = {"--paper": "paper", "--no-search": "no_search", "--no-improve": "no_improve",
          "-q": "quiet", "--quiet": "quiet"}
_INTEGERS = {"seed", "max_expansions", "max_ticks", "max_alternatives"}
_COMPLETION = "_BTPLAN_COMPLETE"
"""click's shell-completion switch for the `btplan` program: the typer app handles it."""


def _word(value: str) -> bool:
    """A value both ways read alike: not empty, and no option-like word (but '-')."""
    return value == "-" or (value != "" and not value.startswith("-"))


def _digits(text: str, least: int, most: int) -> bool:
    """`text` is `least` to `most` ASCII digits (no regular expression to compile)."""
    return least <= len(text) <= most and (not text or (text.isascii() and text.isdigit()))


def _integer(value: str) -> bool:
    """A plain integer: `[0-9]{1,18}`."""
    return _digits(value, 1, 18)


def _decimal(value: str) -> bool:
    r"""A plain decimal: `[0-9]{1,15}(\.[0-9]{0,6})?` or `\.[0-9]{1,6}`."""
    whole, point, fraction = value.partition(".")
    if not point:
        return _digits(whole, 1, 15)
    return _digits(whole, 1, 15) and _digits(fraction, 0, 6) if whole else _digits(
        fraction, 1, 6)


def _typed(name: str, value: str) -> Any:
    """The value as the typer command would pass it, or None to let typer decide."""
    if not _word(value):
        return None
    if name in _INTEGERS:
        return int(value) if _integer(value) else None
    if name == "timeout":
        return float(value) if _decimal(value) else None
    if name == "fmt":
        return value if value in FORMATS else None
    return value


def read_plan_arguments(args: list[str]) -> dict[str, Any] | None:
    """The keyword arguments of `plan_and_write` for `btplan plan ARGS`, or None."""
    given: dict[str, Any] = {}
    positional: list[str] = []
    at = 0
    while at < len(args):
        word = args[at]
        at += 1
        if word in _FLAGS:
            given[_FLAGS[word]] = True
            continue
        name, _, attached = word.partition("=")
        if name in _VALUED and (attached or "=" in word):
            if not name.startswith("--"):
                return None  # `-o=x` means the value `=x` to click
            value = attached
        elif word in _VALUED and at < len(args):
            value = args[at]
            at += 1
        elif _word(word) and len(positional) < 2:
            positional.append(word)
            continue
        else:
            return None
        typed = _typed(_VALUED[name], value)
        if typed is None:
            return None
        given[_VALUED[name]] = typed
    if not positional:
        return None
    if "out_alias" in given:
        given["out"] = given.pop("out_alias")
    return {"domain": positional[0], "problem": positional[1] if positional[1:] else None,
            **given}


def plan_fast(args: list[str]) -> int | None:
    """Run `btplan plan ARGS` without typer and return its exit code; None: use typer."""
    if _COMPLETION in os.environ:
        return None
    arguments = read_plan_arguments(args)
    if arguments is None:
        return None
    from btplan.cli.edge import exit_code_for
    from btplan.cli.interrupts import process_start
    from btplan.cli.planning import plan_and_write

    try:
        plan_and_write(**arguments, started=process_start())
    except (Exception, KeyboardInterrupt) as error:
        return exit_code_for(error)
    return 0


def main_fast() -> None:
    """Exit with `btplan plan`'s code if the lean start could read the arguments."""
    args = sys.argv[1:]
    if args[:1] == ["plan"]:
        code = plan_fast(args[1:])
        if code is not None:
            leave(code)


def leave(code: int) -> NoReturn:
    """End the process with `code` once standard output and error are flushed, without
    tearing the interpreter down: the outputs are written and closed by then, btplan
    registers nothing to run at exit, and freeing every module and object one by one
    took about 5 ms of CPU, a tenth of a small plan run. Should a flush fail (a closed
    pipe), the interpreter exits as usual and reports it as it always did. Code that
    calls `main` and wants it to raise SystemExit replaces this with `sys.exit`."""
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (OSError, ValueError):
        sys.exit(code)
    os._exit(code)
