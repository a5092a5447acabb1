"""The `btplan` command line: one module per command, all on one typer app.

The app (and typer with it) is built on first use of `btplan.cli.app` (PEP 562), so
that the console script can run a plain `btplan plan ...` without it (`cli/lean.py`).
"""

from __future__ import annotations

import gc
import sys

OPTIONAL_PORTS = {"--groot": "1667", "--view": "8765"}
"""Options of `btplan run` whose port may be left out, and the port they then take
(btplan.cli.monitors.with_default_ports): Groot2's default, and the browser view's."""

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from typer import Typer

    app: Typer


def main() -> None:
    """The console script; a bug outside any command still ends in one line and exit 3.

    The cyclic garbage collector is off while the program starts: imports and reading
    the input make tens of thousands of objects that live until the process ends, and
    the collections they set off found nothing to free and took about 5 ms of a 45 ms
    `btplan plan` (cli/planning.py turns it back on before planning).
    """
    gc.disable()
    try:
        from btplan.cli import edge
        from btplan.cli.lean import main_fast

        edge.console = True

        main_fast()  # exits when it could run the command itself
    finally:  # a caller that catches the exit (a test) gets its collector back
        gc.enable()
    from btplan.cli.edge import EXIT_BUG, report_bug

    only_the_command_asked_for(sys.argv[1:2])
    if any(flag in sys.argv for flag in OPTIONAL_PORTS):
        from btplan.cli.monitors import with_default_ports

        sys.argv[1:] = with_default_ports(sys.argv[1:])
    try:
        _the_app()(prog_name="btplan")
    except Exception as error:  # commands report their own; this is the last net
        report_bug(error)
        sys.exit(EXIT_BUG)


def _the_app() -> Typer:
    from btplan.cli import commands as _commands  # noqa: F401  (registers the commands)
    from btplan.cli.typer_app import app as built

    return built


def __getattr__(name: str) -> Any:
    if name == "app":
        return _the_app()
    raise AttributeError(f"module 'btplan.cli' has no attribute {name!r}")


def only_the_command_asked_for(first: list[str]) -> None:
    """Keep on the app only the command that the first argument names, if it names one.

    typer reads the signature of every command (annotations evaluated, parameters
    built) before it runs any; for seven commands that took longer than planning a
    small problem. The command's own parsing, help and errors are unchanged; anything
    else (`btplan --help`, a misspelt command, options before the command) keeps the
    whole app.
    """
    if not first:
        return
    app = _the_app()
    name = first[0]
    commands = [c for c in app.registered_commands
                if (c.name or getattr(c.callback, "__name__", "").replace("_", "-")) == name]
    groups = [g for g in app.registered_groups if g.name == name]
    if commands or groups:
        app.registered_commands, app.registered_groups = commands, groups


__all__ = ["OPTIONAL_PORTS", "app", "main", "only_the_command_asked_for"]
