"""Where errors become one line on stderr and an exit code, without importing typer.

Both ways a command runs share this: the typer app (`typer_app.guarded` wraps every
command) and the lean start of `btplan plan` (`cli/lean.py`), which plans without
building the typer app at all. Our own errors turn into one clean message and an exit
code (2 for bad input, 1 for planning failures); an interrupt exits 130 (143 for
SIGTERM); anything else is a bug: one line that says so and how to report it, exit 3,
and the traceback only with `--debug` or BTPLAN_DEBUG=1.
"""

from __future__ import annotations

import errno
import os
import sys

from btplan.cli.console import LazyConsole, escape
from btplan.errors import BtplanError, InputError, Interrupted, PlanningError
from btplan.limits import abridge, printable

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


class Flag:
    """A switch with `get` and `set`, as a ContextVar has them (contextvars, a compiled
    module, is not worth loading for one switch that each command run sets)."""

    __slots__ = ("value",)

    def __init__(self) -> None:
        self.value = False

    def get(self) -> bool:
        """The switch as last set, False until then (as `ContextVar.get` answers)."""
        return self.value

    def set(self, value: bool) -> None:
        """Set the switch for the command being run; every run sets it, so none inherits it."""
        self.value = value


debug_flag = Flag()
"""Set by `--debug` for the command being run (the group callback sets it every time)."""

stderr = LazyConsole(stderr=True)


console = False
"""Whether btplan runs as the console script (`btplan.cli.main`), which may end the
process with `lean.leave`; a caller that runs the app in its own process (a test) must
get control back."""


class CommandExit(Exception):
    """A command ends here with this exit code, its message already printed."""

    def __init__(self, code: int) -> None:
        super().__init__(code)
        self.code = code


def version() -> str:
    """btplan's installed version, for `--version` and bug reports; "unknown" when run from
    a checkout never installed. importlib.metadata is imported only when asked."""
    from importlib import metadata  # imports email and more: only when asked

    try:
        return metadata.version("btplan")
    except metadata.PackageNotFoundError:  # run from a checkout without installing
        return "unknown"


def format_input_error(error: InputError) -> str:
    """`file:line:col: message`, then the offending line and a caret under the column.

    Message, hint and line are cut to a few hundred characters (btplan/limits.py): only
    quoted input makes them longer, and a terminal full of it helps no one.
    """
    where = f"{error.span}: " if error.span else ""
    hint = f" ({abridge(error.hint)})" if error.hint else ""
    lines = [printable(f"{where}{abridge(error.message)}{hint}")]
    shown = error.excerpt()
    if shown is not None:
        lines.append(f"  {shown[0]}")
        lines.append("  " + " " * shown[1] + "^")
    return "\n".join(lines)


_ENVIRONMENT = {errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EIO, errno.EFBIG}
"""Errors of the machine a command runs on, rather than of btplan."""


def debugging() -> bool:
    """Whether a bug shows its traceback: `--debug` was given, or BTPLAN_DEBUG is set to
    anything but "" or "0" (the same for every command, without changing its flags)."""
    return debug_flag.get() or os.environ.get(DEBUG_ENV, "") not in ("", "0")


def report_bug(error: BaseException) -> None:
    """One line for an unexpected exception; the traceback only when debugging."""
    if debugging():
        import traceback  # not imported at start: only --debug prints one

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


def exit_code_for(error: BaseException) -> int:
    """Say what went wrong on stderr (nothing for a CommandExit) and return the exit code."""
    if isinstance(error, CommandExit):
        return error.code
    if isinstance(error, InputError):
        stderr.print(f"[bold red]error:[/] {escape(format_input_error(error))}")
        return EXIT_BAD_INPUT
    if isinstance(error, PlanningError):
        stderr.print(f"[bold red]failed:[/] {escape(printable(error.reason))}")
        return EXIT_FAILED
    if isinstance(error, Interrupted):
        stderr.print(f"[bold yellow]interrupted:[/] {escape(str(error))}")
        return EXIT_INTERRUPTED
    if isinstance(error, BtplanError):
        stderr.print(f"[bold red]error:[/] {escape(printable(str(error)))}")
        return EXIT_BAD_INPUT
    if isinstance(error, KeyboardInterrupt):
        stderr.print("[bold yellow]interrupted[/]")
        return EXIT_INTERRUPTED
    if isinstance(error, OSError) and error.errno in _ENVIRONMENT:
        # The user's environment (a full disk, a file system gone read-only), not a bug:
        # outputs are written whole or not at all, so the files it would replace are kept.
        where = f"{error.filename}: " if error.filename is not None else ""
        stderr.print(f"[bold red]error:[/] {escape(printable(where))}"
                     f"{escape(error.strerror or str(error))}; nothing was replaced")
        return EXIT_BAD_INPUT
    if isinstance(error, BrokenPipeError):
        # The reader of standard output stopped early (`| head`): not an error, as
        # for ripgrep; later writes (at exit) go nowhere instead of failing again.
        _silence_stdout()
        return EXIT_OK
    report_bug(error)
    return EXIT_BUG
