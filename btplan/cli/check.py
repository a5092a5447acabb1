"""The `btplan check` command: read and validate inputs, then summarise them."""

from __future__ import annotations

import dataclasses
import json
from typing import TYPE_CHECKING, Annotated

import typer

from btplan.cli.typer_app import EXIT_BAD_INPUT, app, format_input_error, guarded, stderr
from btplan.cli.console import LazyConsole, escape
from btplan.errors import InputError, Span

if TYPE_CHECKING:
    from btplan.lang import Collection

stdout = LazyConsole()


EXAMPLES = """Examples:

  btplan check domains/pick_place.bt
  btplan check domain.pddl problem.pddl
  btplan check --json domains/blocksworld.bt | jq '.problems[].name'
  btplan check domains/pick_place_obstacle.bt --ros examples/ros/example2.toml
"""


@app.command(epilog=EXAMPLES)
@guarded
def check(
    files: Annotated[list[str], typer.Argument(
        metavar="FILE", help="Domain and problem files (.bt or .pddl); '-' reads standard input.")],
    as_json: Annotated[
        bool, typer.Option("--json", help="Print the parsed models as JSON instead.")
    ] = False,
    quiet: Annotated[bool, typer.Option(
        "-q", "--quiet", help="Print nothing when all is well; errors only.")] = False,
    ros: Annotated[str | None, typer.Option(
        "--ros", metavar="FILE.toml",
        help="Also check a ROS 2 binding file against the domain and the installed ROS 2 "
             "types (docs/ros.md).", show_default=False)] = None,
) -> None:
    """Check domains and problems; print a summary, or every error with its place."""
    from btplan.lang import InputErrors, collect  # the readers: only when a command reads
    from btplan.shipped import resolve

    try:
        collection = collect([resolve(f) for f in files])
    except InputErrors as errors:
        for error in errors.errors:
            stderr.print(f"[bold red]error:[/] {escape(format_input_error(error))}")
        stderr.print(f"{len(errors.errors)} errors")
        raise typer.Exit(EXIT_BAD_INPUT) from None
    if ros is not None:
        from btplan.cli.ros_world import check_ros_bindings

        if len(collection.domains) != 1:
            raise InputError(f"--ros checks bindings against one domain; {len(collection.domains)} "
                             "were given", Span("--ros", 1, 1))
        bound = check_ros_bindings(ros, collection.domains[0])
        if not quiet:
            stdout.print(escape(bound))
    if quiet:
        return
    for remark in collection.warnings:
        stderr.print(f"[bold yellow]warning:[/] {escape(format_input_error(remark))}")
    if as_json:
        typer.echo(json.dumps(to_json(collection), indent=2))
        return
    stdout.print(summary(collection), markup=True)
    count = len(collection.domains) + len(collection.problems)
    stdout.print(f"[green]ok[/]: {count} definition{'s' if count != 1 else ''} checked")


def to_json(collection: Collection) -> dict[str, object]:
    """The checked domains and problems as plain dicts, every field of their models, for
    `check --json`: scripts read it with jq rather than parse the summary."""
    return {
        "domains": [dataclasses.asdict(d) for d in collection.domains],
        "problems": [dataclasses.asdict(p) for p in collection.problems],
    }


def summary(collection: Collection) -> str:
    """A few lines per domain and per problem, with what a reader checks first.

    Plain lines rather than a table: a table folds long lists at the terminal width,
    and a summary should read the same in a pipe and on any screen.
    """
    from btplan.lang.writers import bt_literal
    from btplan.model import ROOT_TYPE

    lines: list[str] = []
    for domain in collection.domains:
        types = [t.name for t in domain.types if t.name != ROOT_TYPE or t.parent is not None]
        lines += [
            f"[bold]domain[/] {domain.name}",
            _row("types", types),
            _row("predicates", [p.name for p in domain.predicates]),
            _row("actions", [a.name for a in domain.actions]),
            _row("constants", [c.name for c in domain.constants]),
        ]
    for problem in collection.problems:
        lines += [
            f"[bold]problem[/] {problem.name} for {problem.domain}",
            _row("objects", [o.name for o in problem.objects]),
            f"  {'init':<11} {len(problem.init)} fact{'s' if len(problem.init) != 1 else ''}",
            _row("goal", [bt_literal(g) for g in problem.goal]),
        ]
    return "\n".join(lines)


def _row(label: str, names: list[str], limit: int = 12) -> str:
    shown = ", ".join(names[:limit]) + (", ..." if len(names) > limit else "")
    return f"  {label:<11} {len(names)}" + (f": {shown}" if names else "")
