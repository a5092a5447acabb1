"""The `btplan plan` command: backchain a tree offline in the symbolic world and print it."""

from __future__ import annotations

import time  # noqa: F401  (tests reach the clock of the progress line through this module)
from enum import Enum
from typing import Annotated

import typer

from btplan.cli.outputs import STDIO
from btplan.cli.planning import (
    DEFAULT_TIMEOUT, Progress, default_format, plan_and_write, plan_text, summary,
)
from btplan.cli.typer_app import app, guarded


class Format(str, Enum):
    """What `btplan plan -f` writes the tree as; when no format is given, `default_format`
    picks one from where the output goes."""
    xml = "xml"
    dot = "dot"
    json = "json"
    ascii = "ascii"


EXAMPLES = """Examples:

  btplan plan domains/pick_place.bt                      # the tree as text on a terminal
  btplan plan domains/pick_place.bt -o tree.xml          # BehaviorTree.CPP v4 XML
  btplan plan domain.pddl problem.pddl -f dot | dot -Tsvg > tree.svg
  btplan plan domains/blocksworld.bt --plan-out sas_plan --timeout 60
  btplan plan domain.pddl scene.pddl --goal '(and (on a b) (on b c))'
"""


@app.command(name="plan", epilog=EXAMPLES)
@guarded
def plan_command(
    domain: Annotated[str, typer.Argument(
        metavar="DOMAIN", help="Domain (.bt or .pddl), or domain and problem in one .bt file; "
        "'-' reads standard input.")],
    problem: Annotated[str | None, typer.Argument(
        metavar="PROBLEM", help="Problem file, when it is not in DOMAIN.", show_default=False)
    ] = None,
    fmt: Annotated[Format | None, typer.Option(
        "-f", "--format",
        help="Tree format: ascii on a terminal, json when piped, by extension for -o.",
        show_default=False)] = None,
    out: Annotated[str, typer.Option("-o", "--output", metavar="FILE",
                                     help="Write the tree to FILE ('-': standard output).")
                   ] = STDIO,
    out_alias: Annotated[str | None, typer.Option("--out", hidden=True)] = None,
    plan_out: Annotated[str | None, typer.Option(
        "--plan-out", metavar="FILE", show_default=False,
        help="Write the actions of the final run in IPC plan format ('-': standard output).")
    ] = None,
    trace_expansions: Annotated[str | None, typer.Option(
        "--trace-expansions", metavar="DIR",
        help="Write the tree after every expansion (DOT and JSON) into DIR.", show_default=False)
    ] = None,
    seed: Annotated[int, typer.Option("--seed", metavar="N",
                                      help="Seed of the symbolic world.")] = 0,
    max_expansions: Annotated[int, typer.Option(
        "--max-expansions", metavar="N", help="Give up after N expansions.")] = 1000,
    max_ticks: Annotated[int, typer.Option("--max-ticks", metavar="N",
                                           help="Give up after N ticks.")] = 100_000,
    max_alternatives: Annotated[int | None, typer.Option(
        "--max-alternatives", metavar="N",
        help="Achievers kept per condition. Unset: 4, widened once if planning fails; "
             "given: exactly N, in one strategy, without the whole-goal search.",
        show_default=False)] = None,
    paper: Annotated[bool, typer.Option(
        "--paper", help="Algorithms 1-3 exactly as published, without btplan's extensions.")
    ] = False,
    no_search: Annotated[bool, typer.Option(
        "--no-search", help="Never search (the last resort: for a stuck condition, or for "
        "the whole goal when backchaining fails).")
    ] = False,
    no_improve: Annotated[bool, typer.Option(
        "--no-improve", help="Keep the executed plan as backchaining found it (no action "
        "elimination, no neighbourhood search; the tree stays the backchained one).")
    ] = False,
    timeout: Annotated[float, typer.Option(
        "--timeout", metavar="SECONDS",
        help="Give up after SECONDS seconds from the start, reading and grounding included "
             "(exit 1); 0: no limit.")] = DEFAULT_TIMEOUT,
    quiet: Annotated[bool, typer.Option(
        "-q", "--quiet", help="No progress and no summary on standard error.")] = False,
    max_memory: Annotated[str, typer.Option(
        "--max-memory", metavar="SIZE",
        help="Stop (exit 1) when the planner's memory would grow past SIZE (2G, 500M; 0: no "
             "limit); by default 80% of the machine's memory.")] = "auto",
    goal: Annotated[str | None, typer.Option(
        "--goal", metavar="CONDITION", show_default=False,
        help="Plan this goal instead of the problem's, from the same objects and initial "
             "state: one PDDL condition, such as '(and (on a b) (not (clear c)))'.")] = None,
) -> None:
    """Build a reactive BT for the problem by planning and acting in the symbolic world.

    The tree goes to standard output (or -o FILE), the summary to standard error.
    Ctrl-C stops at the next tick: nothing is written, the summary says how far it got.
    """
    plan_and_write(domain, problem, fmt.value if fmt is not None else None,
                   out_alias if out_alias is not None else out, plan_out, trace_expansions,
                   seed, max_expansions, max_ticks, max_alternatives, paper, no_search,
                   timeout, quiet, no_improve, max_memory, goal=goal)


__all__ = ["DEFAULT_TIMEOUT", "Format", "Progress", "default_format", "plan_command",
           "plan_text", "summary"]
