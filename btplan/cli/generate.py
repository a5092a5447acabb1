"""The `btplan generate` command: classic problems of any size, as PDDL or .bt text."""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum
from typing import Annotated

import typer

from btplan.cli.typer_app import app, guarded, stderr
from btplan.cli.interrupts import Interrupts
from btplan.cli.outputs import STDIO, Output, check_outputs, write_atomic
from btplan.errors import InputError
from btplan.lang.generators import assembly, blocksworld, gripper, logistics, render
from btplan.model import Domain, Problem

generate_app = typer.Typer(
    help="Generate planning problems (blocksworld, gripper, logistics, assembly) from a seed.",
    epilog="Examples:\n\n"
           "  btplan generate blocksworld --blocks 8 --seed 3 -o bw.pddl\n"
           "  btplan generate gripper --balls 6 --format bt --problem-only\n",
    no_args_is_help=True,
)
app.add_typer(generate_app, name="generate")


class Format(str, Enum):
    """The language `btplan generate` writes: PDDL, or btplan's own .bt."""
    pddl = "pddl"
    bt = "bt"


Seed = Annotated[int, typer.Option(
    "--seed", metavar="N", help="Random seed: the same seed, the same text.")]
Fmt = Annotated[Format, typer.Option("-f", "--format", help="pddl, or btplan's own .bt language.")]
DomainOnly = Annotated[bool, typer.Option("--domain-only", help="Write only the domain.")]
ProblemOnly = Annotated[bool, typer.Option("--problem-only", help="Write only the problem.")]
Out = Annotated[str, typer.Option(
    "-o", "--output", metavar="FILE", help="Write to FILE ('-': standard output).")]


def emit(make: Callable[[], tuple[Domain, Problem]], fmt: Format, domain_only: bool,
         problem_only: bool, out: str) -> None:
    """Check the flags and the output, generate, and write unless a signal came meanwhile."""
    if domain_only and problem_only:
        raise InputError("--domain-only and --problem-only exclude each other")
    check_outputs(Output("-o/--output", out))
    with Interrupts() as interrupted:
        domain_text, problem_text = render(*make(), fmt=fmt.value)
    if interrupted():
        stderr.print("[bold yellow]interrupted[/]: nothing written")
        raise typer.Exit(interrupted.exit_code)
    if domain_only:
        text = domain_text
    elif problem_only:
        text = problem_text
    else:
        text = domain_text + "\n" + problem_text
    write_atomic(out, text)


def _size(value: int, flag: str, least: int = 1) -> int:
    if value < least:
        raise InputError(f"{flag} must be at least {least}, got {value}")
    return value


@generate_app.command("blocksworld", epilog="Example:\n\n  btplan generate blocksworld --blocks 8 --seed 3 -o bw.pddl\n")
@guarded
def generate_blocksworld(
    blocks: Annotated[int, typer.Option("--blocks", metavar="N", help="Number of blocks.")] = 5,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Random towers to random towers, with the classic four operators."""
    n = _size(blocks, "--blocks")
    emit(lambda: blocksworld(n, seed), fmt, domain_only, problem_only, out)


@generate_app.command("gripper", epilog="Example:\n\n  btplan generate gripper --balls 6 --format bt | btplan plan -\n")
@guarded
def generate_gripper(
    balls: Annotated[int, typer.Option("--balls", metavar="N", help="Number of balls.")] = 4,
    rooms: Annotated[int, typer.Option("--rooms", metavar="N", help="Number of rooms.")] = 2,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """A two-handed robot carries balls between rooms."""
    n, r = _size(balls, "--balls"), _size(rooms, "--rooms", 2)
    emit(lambda: gripper(n, seed, rooms=r), fmt, domain_only, problem_only, out)


@generate_app.command("logistics", epilog="Example:\n\n  btplan generate logistics --packages 5 --domain-only -o log.pddl\n")
@guarded
def generate_logistics(
    packages: Annotated[int, typer.Option(
        "--packages", metavar="N", help="Number of packages.")] = 3,
    cities: Annotated[int, typer.Option("--cities", metavar="N", help="Number of cities.")] = 2,
    locations: Annotated[int, typer.Option(
        "--locations", metavar="N", help="Places per city.")] = 2,
    airplanes: Annotated[int, typer.Option(
        "--airplanes", metavar="N", help="Number of airplanes.")] = 1,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Trucks within cities, airplanes between airports, packages to deliver."""
    sizes = (_size(packages, "--packages"), _size(cities, "--cities"),
             _size(locations, "--locations"), _size(airplanes, "--airplanes"))
    emit(lambda: logistics(sizes[0], seed, cities=sizes[1], locations=sizes[2],
                           airplanes=sizes[3]),
         fmt, domain_only, problem_only, out)


@generate_app.command("assembly", epilog="Example:\n\n  btplan generate assembly --parts 8 --seed 2 --format bt | btplan plan -\n")
@guarded
def generate_assembly(
    parts: Annotated[int, typer.Option("--parts", metavar="N", help="Number of parts.")] = 6,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Two arms mount parts in order; parts lying opening down need a handover."""
    emit(lambda: assembly(_size(parts, "--parts"), seed), fmt, domain_only, problem_only, out)
