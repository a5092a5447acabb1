"""The typer application, the stderr console, and the one place errors become exit codes.

Every command is wrapped by `guarded`: our own errors turn into one clean message and
an exit code (2 for bad input, 1 for planning failures); anything else is a bug and
keeps its traceback.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import ParamSpec, TypeVar

import typer
from rich.console import Console
from rich.markup import escape

from btplan.errors import BtplanError, InputError, PlanningError
from btplan.limits import abridge, excerpt

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_BAD_INPUT = 2

app = typer.Typer(
    name="btplan",
    help="Turn planning domains into reactive Behavior Trees, export them, and run them.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)

stderr = Console(stderr=True, highlight=False, soft_wrap=True)

P = ParamSpec("P")
R = TypeVar("R")


def format_input_error(error: InputError) -> str:
    """`file:line:col: message`, then the offending line and a caret under the column.

    Message, hint and line are cut to a few hundred characters (btplan/limits.py): only
    quoted input makes them longer, and a terminal full of it helps no one.
    """
    where = f"{error.span}: " if error.span else ""
    hint = f" ({abridge(error.hint)})" if error.hint else ""
    lines = [f"{where}{abridge(error.message)}{hint}"]
    if error.source_line is not None and error.span is not None:
        text, column = excerpt(error.source_line, error.span.column)
        lines.append(f"  {text}")
        lines.append("  " + " " * (column - 1) + "^")
    return "\n".join(lines)


def guarded(command: Callable[P, R]) -> Callable[P, R]:
    """Turn btplan's own exceptions into a message on stderr and an exit code."""

    @functools.wraps(command)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return command(*args, **kwargs)
        except InputError as error:
            stderr.print(f"[bold red]error:[/] {escape(format_input_error(error))}")
            raise typer.Exit(EXIT_BAD_INPUT) from None
        except PlanningError as error:
            stderr.print(f"[bold red]failed:[/] {escape(error.reason)}")
            raise typer.Exit(EXIT_FAILED) from None
        except BtplanError as error:
            stderr.print(f"[bold red]error:[/] {escape(str(error))}")
            raise typer.Exit(EXIT_BAD_INPUT) from None

    return wrapper
