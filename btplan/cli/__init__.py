"""The `btplan` command line: one module per command, all on one typer app."""

from btplan.cli import commands as _commands  # noqa: F401  (registers the commands)
from btplan.cli.app import app


def main() -> None:
    app()


__all__ = ["app", "main"]
