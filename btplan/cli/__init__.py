"""The `btplan` command line: one module per command, all on one typer app."""

import sys

from btplan.cli import commands as _commands  # noqa: F401  (registers the commands)
from btplan.cli.app import EXIT_BUG, app, report_bug


def main() -> None:
    """The console script; a bug outside any command still ends in one line and exit 3."""
    try:
        app(prog_name="btplan")
    except Exception as error:  # commands report their own; this is the last net
        report_bug(error)
        sys.exit(EXIT_BUG)


__all__ = ["app", "main"]
