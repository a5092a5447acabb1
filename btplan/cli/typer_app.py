"""The typer application: every command registers on it; `guarded` turns what a command
raises into a message and an exit code (btplan/cli/edge.py says which).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Annotated, ParamSpec, TypeVar

import typer
from typer.exceptions import TyperException

from btplan.cli.edge import (
    DEBUG_ENV, EXIT_BAD_INPUT, EXIT_BUG, EXIT_CODES, EXIT_FAILED, EXIT_INTERRUPTED, EXIT_OK,
    EXIT_TERMINATED, ISSUES, CommandExit, debug_flag, debugging, exit_code_for,
    format_input_error, report_bug, stderr, version,
)
from btplan.cli.help import Group

app = typer.Typer(
    name="btplan",
    cls=Group,
    help="Turn planning domains into reactive Behavior Trees, export them, and run them.",
    epilog="Exit codes: 0 done, 1 no tree or goal not reached, 2 bad input or usage, "
           "3 a bug, 130 Ctrl-C, 143 SIGTERM. Reference: docs/cli.md.",
    no_args_is_help=True,
    add_completion=True,
    pretty_exceptions_enable=False,
    context_settings={"help_option_names": ["-h", "--help"]},
)

P = ParamSpec("P")
R = TypeVar("R")


def _show_version(value: bool) -> None:
    if value:
        typer.echo(f"btplan {version()}")
        raise typer.Exit(EXIT_OK)


@app.callback()
def main_options(
    show_version: Annotated[bool, typer.Option(
        "--version", "-V", callback=_show_version, is_eager=True,
        help="Print the version and exit.")] = False,
    debug: Annotated[bool, typer.Option(
        "--debug", help="On an internal error, print the traceback (as BTPLAN_DEBUG=1 does).")
    ] = False,
) -> None:
    """Turn planning domains into reactive Behavior Trees, export them, and run them."""
    debug_flag.set(debug)


def guarded(command: Callable[P, R]) -> Callable[P, R]:
    """Turn exceptions into a message on stderr and an exit code (see EXIT_CODES)."""

    @functools.wraps(command)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return command(*args, **kwargs)
        except (typer.Exit, typer.Abort, TyperException):
            raise
        except (Exception, KeyboardInterrupt) as error:
            raise typer.Exit(exit_code_for(error)) from None

    return wrapper


__all__ = [
    "DEBUG_ENV", "EXIT_BAD_INPUT", "EXIT_BUG", "EXIT_CODES", "EXIT_FAILED", "EXIT_INTERRUPTED",
    "EXIT_OK", "EXIT_TERMINATED", "ISSUES", "CommandExit", "app", "debugging",
    "format_input_error", "guarded", "report_bug", "stderr", "version",
]
