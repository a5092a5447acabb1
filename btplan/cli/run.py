"""The `btplan run` command: plan and act at once in a world, with external agents."""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from enum import Enum
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.markup import escape
from rich.table import Table

from btplan import acting
from btplan.bt import Node, Status
from btplan.cli.app import EXIT_FAILED, app, guarded, stderr
from btplan.errors import InputError, Span, WorldError
from btplan.io import read_text, write_atomic
from btplan.acting.live_view import LiveView
from btplan.model import Task
from btplan.acting.records import RunSummary, TickRecord, records_to_jsonl
from btplan.worlds.agents import Agent
from btplan.worlds.disturb import DisturbSpec, parse_scenario, parse_spec


class Sim(str, Enum):
    symbolic = "symbolic"
    pybullet = "pybullet"


@app.command()
@guarded
def run(
    files: Annotated[list[str], typer.Argument(
        help="The domain, and the problem if it is in another file (.bt or .pddl).")],
    sim: Annotated[Sim, typer.Option(help="The world to act in.")] = Sim.symbolic,
    disturb: Annotated[list[str] | None, typer.Option(
        "--disturb", metavar="SPEC",
        help="An external agent, e.g. undo@5, help:Pick(cube)@3, set:free(t)@p=0.05, "
             "fail:MoveTo@2 (repeatable; see docs/cli.md).")] = None,
    scenario: Annotated[str | None, typer.Option(
        help="A file of disturbance specs, one per line; with --sim pybullet, a scene "
             "(.toml file, or the name of a shipped scene).")] = None,
    seed: Annotated[int, typer.Option(help="Seed of every random choice in the run.")] = 0,
    max_ticks: Annotated[int, typer.Option(min=1, help="Give up after this many ticks.")] = 1000,
    fail_prob: Annotated[list[str] | None, typer.Option(
        "--fail-prob", metavar="ACTION=P",
        help="Make each tick of an action fail with probability P (repeatable).")] = None,
    trace: Annotated[str | None, typer.Option(
        metavar="FILE.jsonl", help="Write one JSON line per tick.")] = None,
    plan_out: Annotated[str | None, typer.Option(
        metavar="PLAN", help="Write the executed actions in IPC plan format ('-': stdout).")] = None,
    rate: Annotated[float | None, typer.Option(
        min=0.01, metavar="HZ", help="Ticks per second, to watch (default: as fast as possible).")
    ] = None,
    quiet: Annotated[bool, typer.Option(help="No live view and no progress; the summary only.")
                     ] = False,
    gui: Annotated[bool, typer.Option(help="Open the PyBullet window (--sim pybullet).")] = False,
    record: Annotated[str | None, typer.Option(
        metavar="FILE", help="Record the PyBullet run to a file (--sim pybullet).")] = None,
) -> None:
    """Run Algorithm 1 online: tick the tree, expand it when it fails, let agents disturb it.

    Exit 0 when the goal is reached, 1 when it is not within --max-ticks, 2 on bad input.
    """
    if len(files) > 2:
        raise InputError("give a domain and at most one problem file", Span(files[2], 1, 1))
    task = acting.load(*files)
    specs = [parse_spec(text, Span("--disturb", 1, 1)) for text in disturb or []]
    scene: str | None = None
    if scenario is not None:
        if sim is Sim.pybullet and (scenario.endswith(".toml") or not Path(scenario).is_file()):
            scene = scenario
        else:
            specs.extend(parse_scenario(read_text(scenario), scenario))
    world, scene_agents = open_world(task, sim, scene, seed, gui, record, probabilities(fail_prob))
    try:
        result = _act(task, world, specs, scene_agents, seed, max_ticks, rate, quiet)
    finally:
        if hasattr(world, "close"):
            world.close()
    if trace is not None:
        write_atomic(trace, records_to_jsonl(result.records))
    if plan_out is not None:
        write_atomic(plan_out, result.plan_text())
    stderr.print(summary_table(result.reached, result.reason, result.summary()))
    if not result.reached:
        stderr.print(f"[bold red]failed:[/] {escape(result.reason)}")
        raise typer.Exit(EXIT_FAILED)


def _act(task: Task, world: Any, specs: list[DisturbSpec], scene_agents: list[Agent], seed: int,
         max_ticks: int, rate: float | None, quiet: bool) -> acting.RunOutcome:
    if quiet:
        view = None
    elif stderr.is_terminal:
        with LiveView(stderr) as live:
            return acting.run(task, disturb=specs, agents=scene_agents, world=world, seed=seed,
                           max_ticks=max_ticks, view=live.show, rate=rate)
    else:
        view = progress_line
    return acting.run(task, disturb=specs, agents=scene_agents, world=world, seed=seed,
                   max_ticks=max_ticks, view=view, rate=rate)


def progress_line(root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
    """Without a terminal, one line per event (disturbance, expansion) instead of a live tree."""
    for d in record.disturbances:
        stderr.print(f"tick {record.tick}: {escape(d.agent)}: {escape(d.description)}")
    for e in record.expansions:
        stderr.print(f"tick {record.tick}: expanded {escape(e.condition)} with "
                     f"{escape(', '.join(e.achievers) or 'no achiever')}")


def probabilities(items: list[str] | None) -> dict[str, float]:
    """Parse `--fail-prob Pick=0.2` flags into a per-action failure probability."""
    table: dict[str, float] = {}
    for item in items or []:
        name, _, value = item.partition("=")
        try:
            p = float(value)
        except ValueError:
            p = -1.0
        if not name or not 0.0 <= p <= 1.0:
            raise InputError("expected ACTION=P with P between 0 and 1",
                             Span("--fail-prob", 1, len(name) + 2 if name else 1), None, item)
        table[name.strip()] = p
    return table


def open_world(task: Task, sim: Sim, scene: str | None, seed: int, gui: bool,
               record: str | None, failure: dict[str, float]) -> tuple[Any, list[Agent]]:
    """The world to act in, and the agents that come with it (a scene's scripted events)."""
    unknown = sorted(set(failure) - set(task.domain.action_map))
    if unknown:
        raise InputError(f"unknown action '{unknown[0]}'", Span("--fail-prob", 1, 1))
    if sim is Sim.symbolic:
        if gui or record:
            raise InputError("--gui and --record need --sim pybullet", Span("--sim", 1, 1))
        from btplan.worlds.symbolic import SymbolicWorld

        return SymbolicWorld(task, seed=seed, failure_probability=failure), []
    try:
        module = importlib.import_module("btplan.worlds.pybullet")
    except ImportError as error:
        raise WorldError(f"the PyBullet world is not available ({error}); "
                         "install the extra with: pip install 'btplan[sim]'") from None
    opener = getattr(module, "open_world", None)
    if opener is None:
        raise WorldError("this installation has no PyBullet world")
    scenes = getattr(module, "SCENES", None)
    if scene is not None and not Path(scene).exists() and scenes is not None:
        named = Path(scenes) / f"{scene}.toml"
        scene = str(named) if named.exists() else scene
    world = opener(task, scene=scene, seed=seed, gui=gui, record=record)
    return world, list(world.scene_agents())


def summary_table(reached: bool, reason: str, total: RunSummary) -> Table:
    """Outcome, ticks, expansions (and when), conflicts, actions, disturbances."""
    table = Table(title="btplan run", show_header=False, box=None)
    table.add_column(style="bold")
    table.add_column(overflow="fold")
    outcome = "[green]goal reached[/]" if reached else f"[red]not reached[/]: {escape(reason)}"
    table.add_row("outcome", outcome)
    table.add_row("ticks", str(total.ticks))
    grown = ", ".join(f"{e.condition} @{tick}" for tick, e in total.expansions)
    table.add_row("expansions", f"{len(total.expansions)}" + (f" ({escape(grown)})" if grown else ""))
    table.add_row("conflicts resolved", str(total.conflicts_resolved))
    table.add_row("executed", _listing(total.finished))
    table.add_row("halted", _listing(total.halted))
    table.add_row("failed", _listing(total.failed))
    table.add_row("disturbances",
                  _listing([f"@{d.tick} {d.description}" for d in total.disturbances]))
    return table


def _listing(items: list[str]) -> str:
    return f"{len(items)}" + (f": {escape(', '.join(items))}" if items else "")
