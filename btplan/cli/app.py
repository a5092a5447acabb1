"""The typer application, the stderr console, and the one place errors become exit codes.

Every command is wrapped by `guarded`: our own errors turn into one clean message and
an exit code (2 for bad input, 1 for planning failures); an interrupt exits 130 (143
for SIGTERM); anything else is a bug: one line that says so and how to report it,
exit 3, and the traceback only with `--debug` or BTPLAN_DEBUG=1.
"""

from __future__ import annotations

import functools
import os
import sys
import traceback
from collections.abc import Callable
from contextvars import ContextVar
from typing import Annotated, ParamSpec, TypeVar

import typer
from typer.exceptions import TyperException

from btplan.cli.console import LazyConsole, escape
from btplan.cli.help import Group
from btplan.errors import BtplanError, InputError, Interrupted, PlanningError
from btplan.limits import abridge

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_BAD_INPUT = 2
EXIT_BUG = 3
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143
EXIT_CODES = {
    EXIT_OK: "done",
    EXIT_FAILED: "no tree found, or the goal not reached within the budget (a reason on stderr)",
    EXIT_BAD_INPUT: "bad input or usage (file:line:col, or the flag and the path)",
    EXIT_BUG: "a bug in btplan (please report it)",
    EXIT_INTERRUPTED: "interrupted by Ctrl-C (SIGINT); the summary says what was done",
    EXIT_TERMINATED: "stopped by SIGTERM; the summary says what was done",
}
"""The exit codes of every command, as docs/cli.md lists them."""

ISSUES = "https://github.com/btplan/btplan/issues"
DEBUG_ENV = "BTPLAN_DEBUG"
_debug_flag: ContextVar[bool] = ContextVar("btplan_debug", default=False)
"""Set by `--debug` for the command being run (the group callback sets it every time)."""

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

stderr = LazyConsole(stderr=True)

P = ParamSpec("P")
R = TypeVar("R")


def version() -> str:
    from importlib import metadata  # imports email and more: only when asked

    try:
        return metadata.version("btplan")
    except metadata.PackageNotFoundError:  # run from a checkout without installing
        return "unknown"


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
    _debug_flag.set(debug)


def format_input_error(error: InputError) -> str:
    """`file:line:col: message`, then the offending line and a caret under the column.

    Message, hint and line are cut to a few hundred characters (btplan/limits.py): only
    quoted input makes them longer, and a terminal full of it helps no one.
    """
    where = f"{error.span}: " if error.span else ""
    hint = f" ({abridge(error.hint)})" if error.hint else ""
    lines = [f"{where}{abridge(error.message)}{hint}"]
    shown = error.excerpt()
    if shown is not None:
        lines.append(f"  {shown[0]}")
        lines.append("  " + " " * shown[1] + "^")
    return "\n".join(lines)


def debugging() -> bool:
    return _debug_flag.get() or os.environ.get(DEBUG_ENV, "") not in ("", "0")


def report_bug(error: BaseException) -> None:
    """One line for an unexpected exception; the traceback only when debugging."""
    if debugging():
        stderr.print(escape("".join(traceback.format_exception(error))), end="")
    where = "" if debugging() else f" (run again with --debug or {DEBUG_ENV}=1 for details)"
    stderr.print(f"[bold red]internal error:[/] {escape(type(error).__name__)}: "
                 f"{escape(str(error))}. This is a bug in btplan {version()}; please report "
                 f"it with the command you ran at {ISSUES}{where}")


def _silence_stdout() -> None:
    try:
        sink = os.open(os.devnull, os.O_WRONLY)
        os.dup2(sink, sys.stdout.fileno())
        os.close(sink)
    except (OSError, ValueError):  # stdout is no real file (a test runner's buffer)
        pass


def guarded(command: Callable[P, R]) -> Callable[P, R]:
    """Turn exceptions into a message on stderr and an exit code (see EXIT_CODES)."""

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
        except Interrupted as error:
            stderr.print(f"[bold yellow]interrupted:[/] {escape(str(error))}")
            raise typer.Exit(EXIT_INTERRUPTED) from None
        except BtplanError as error:
            stderr.print(f"[bold red]error:[/] {escape(str(error))}")
            raise typer.Exit(EXIT_BAD_INPUT) from None
        except KeyboardInterrupt:
            stderr.print("[bold yellow]interrupted[/]")
            raise typer.Exit(EXIT_INTERRUPTED) from None
        except BrokenPipeError:
            # The reader of standard output stopped early (`| head`): not an error, as
            # for ripgrep; later writes (at exit) go nowhere instead of failing again.
            _silence_stdout()
            raise typer.Exit(EXIT_OK) from None
        except (typer.Exit, typer.Abort, TyperException):
            raise
        except Exception as error:
            report_bug(error)
            raise typer.Exit(EXIT_BUG) from None

    return wrapper
