"""The `btplan generate` command: classic problems of any size, as PDDL or .bt text."""

from __future__ import annotations

from enum import Enum
from typing import Annotated

import typer

from btplan.cli.app import app, guarded
from btplan.errors import InputError
from btplan.io import STDIO, write_atomic
from btplan.lang.generators import assembly, blocksworld, gripper, logistics, render
from btplan.model import Domain, Problem

generate_app = typer.Typer(
    help="Generate classic planning problems (blocksworld, gripper, logistics) from a seed.",
    no_args_is_help=True,
)
app.add_typer(generate_app, name="generate")


class Format(str, Enum):
    pddl = "pddl"
    bt = "bt"


Seed = Annotated[int, typer.Option("--seed", help="Random seed: the same seed, the same text.")]
Fmt = Annotated[Format, typer.Option("--format", help="pddl, or btplan's own .bt language.")]
DomainOnly = Annotated[bool, typer.Option("--domain-only", help="Write only the domain.")]
ProblemOnly = Annotated[bool, typer.Option("--problem-only", help="Write only the problem.")]
Out = Annotated[str, typer.Option("-o", "--output", help="Output file; '-' is standard output.")]


def emit(
    pair: tuple[Domain, Problem], fmt: Format, domain_only: bool, problem_only: bool, out: str
) -> None:
    if domain_only and problem_only:
        raise InputError("--domain-only and --problem-only exclude each other")
    domain_text, problem_text = render(*pair, fmt=fmt.value)
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


@generate_app.command("blocksworld")
@guarded
def generate_blocksworld(
    blocks: Annotated[int, typer.Option("--blocks", help="Number of blocks.")] = 5,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Random towers to random towers, with the classic four operators."""
    emit(blocksworld(_size(blocks, "--blocks"), seed), fmt, domain_only, problem_only, out)


@generate_app.command("gripper")
@guarded
def generate_gripper(
    balls: Annotated[int, typer.Option("--balls", help="Number of balls.")] = 4,
    rooms: Annotated[int, typer.Option("--rooms", help="Number of rooms.")] = 2,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """A two-handed robot carries balls between rooms."""
    pair = gripper(_size(balls, "--balls"), seed, rooms=_size(rooms, "--rooms", 2))
    emit(pair, fmt, domain_only, problem_only, out)


@generate_app.command("logistics")
@guarded
def generate_logistics(
    packages: Annotated[int, typer.Option("--packages", help="Number of packages.")] = 3,
    cities: Annotated[int, typer.Option("--cities", help="Number of cities.")] = 2,
    locations: Annotated[int, typer.Option("--locations", help="Places per city.")] = 2,
    airplanes: Annotated[int, typer.Option("--airplanes", help="Number of airplanes.")] = 1,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Trucks within cities, airplanes between airports, packages to deliver."""
    pair = logistics(
        _size(packages, "--packages"),
        seed,
        cities=_size(cities, "--cities"),
        locations=_size(locations, "--locations"),
        airplanes=_size(airplanes, "--airplanes"),
    )
    emit(pair, fmt, domain_only, problem_only, out)


@generate_app.command("assembly")
@guarded
def generate_assembly(
    parts: Annotated[int, typer.Option("--parts", help="Number of parts.")] = 6,
    seed: Seed = 0,
    fmt: Fmt = Format.pddl,
    domain_only: DomainOnly = False,
    problem_only: ProblemOnly = False,
    out: Out = STDIO,
) -> None:
    """Two arms mount parts in order; parts lying opening down need a handover."""
    emit(assembly(_size(parts, "--parts"), seed), fmt, domain_only, problem_only, out)
