"""The `btplan run` command: plan and act at once in a world, with external agents."""

from __future__ import annotations

import importlib
import sys
import time
from collections.abc import Callable, Mapping
from enum import Enum
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Annotated, Any, Self

import typer

from btplan.cli.typer_app import EXIT_FAILED, app, guarded, stderr
from btplan.cli.console import escape
from btplan.cli.interrupts import Interrupts
from btplan.cli.outputs import STDIO, LineStream, Output, check_outputs, write_atomic
from btplan.errors import InputError, Span, WorldError
from btplan.io import read_text

if TYPE_CHECKING:
    from rich.table import Table

    from btplan import acting
    from btplan.acting.records import TickRecord
    from btplan.bt import Node, Status
    from btplan.model import Task
    from btplan.worlds.agents import Agent
    from btplan.worlds.disturb import DisturbSpec


class Sim(str, Enum):
    symbolic = "symbolic"
    pybullet = "pybullet"


EXAMPLES = """Examples:

  btplan run domains/pick_place.bt --disturb undo:Pick@11 --rate 4
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist --extended
  btplan run domains/youbot.bt --sim pybullet -q --trace run.jsonl --plan-out p.plan
  btplan run domains/pick_place.bt --plan-out - | wc -l
"""


@app.command(epilog=EXAMPLES)
@guarded
def run(
    domain: Annotated[str, typer.Argument(
        metavar="DOMAIN", help="Domain (.bt or .pddl), or domain and problem in one .bt file.")],
    problem: Annotated[str | None, typer.Argument(
        metavar="PROBLEM", help="Problem file, when it is not in DOMAIN.", show_default=False)
    ] = None,
    sim: Annotated[Sim, typer.Option("--sim", help="The world to act in.")] = Sim.symbolic,
    disturb: Annotated[list[str] | None, typer.Option(
        "--disturb", metavar="SPEC",
        help="An external agent, e.g. undo@5, help:Pick(cube)@3, set:free(t)@p=0.05, "
             "fail:MoveTo@2 (repeatable; see docs/cli.md).")] = None,
    scenario: Annotated[str | None, typer.Option(
        "--scenario", metavar="FILE",
        help="A file of disturbance specs, one per line; with --sim pybullet, a scene "
             "(.toml file, or the name of a shipped scene).")] = None,
    seed: Annotated[int, typer.Option(
        "--seed", metavar="N", help="Seed of every random choice in the run.")] = 0,
    max_ticks: Annotated[int, typer.Option(
        "--max-ticks", min=1, metavar="N", help="Give up after N ticks (exit 1).")] = 1000,
    timeout: Annotated[float | None, typer.Option(
        "--timeout", metavar="SECONDS", help="Give up after SECONDS seconds (exit 1).",
        show_default=False)] = None,
    fail_prob: Annotated[list[str] | None, typer.Option(
        "--fail-prob", metavar="ACTION=P",
        help="Make each tick of an action fail with probability P (repeatable).")] = None,
    trace: Annotated[str | None, typer.Option(
        "--trace", metavar="FILE",
        help="Write one JSON line per tick, as it happens ('-': standard output).")] = None,
    plan_out: Annotated[str | None, typer.Option(
        "--plan-out", metavar="FILE",
        help="Write the executed actions in IPC plan format ('-': standard output).")] = None,
    rate: Annotated[float | None, typer.Option(
        "--rate", min=0.01, metavar="HZ",
        help="Ticks per second, to watch (default: as fast as possible).")] = None,
    quiet: Annotated[bool, typer.Option(
        "-q", "--quiet", help="No live view and no progress; the summary only.")] = False,
    extended: Annotated[bool, typer.Option(
        "--extended",
        help="Act as `btplan sweep --method btplan` measures it (docs/reactivity.md): up to "
             "64 expansions per tick, look-ahead, scoped moves, goal credit, a halted "
             "action finished first, a failing action retried until --max-ticks. Without "
             "it, the loop of Algorithm 1, one expansion per tick.")
    ] = False,
    gui: Annotated[bool, typer.Option(
        "--gui", help="Open the PyBullet window (--sim pybullet).")] = False,
    record: Annotated[str | None, typer.Option(
        "--record", metavar="FILE.gif", help="Record the PyBullet run to a GIF (--sim pybullet).")
    ] = None,
) -> None:
    """Run Algorithm 1 online: tick the tree, expand it when it fails, let agents disturb it.

    Exit 0 when the goal is reached, 1 when it is not within --max-ticks or --timeout,
    2 on bad input. Ctrl-C (or SIGTERM) stops at the next tick: the running action is
    halted, the trace and the plan keep every finished tick, the summary is printed,
    and the exit code is 130 (143).
    """
    # The acting layer and the worlds are imported here: every command's module is
    # imported when btplan starts, and only this command (and sweep) acts.
    from btplan import acting
    from btplan.shipped import resolve
    from btplan.worlds.disturb import parse_scenario, parse_spec

    if timeout is not None and timeout <= 0:
        raise InputError(f"--timeout must be positive, got {timeout:g}")
    check_outputs(Output("--trace", trace), Output("--plan-out", plan_out),
                  Output("--record", record))
    task = acting.load(resolve(domain), *([problem] if problem is not None else []))
    specs = [parse_spec(text, Span("--disturb", 1, 1)) for text in disturb or []]
    scene: str | None = None
    if scenario is not None:
        if sim is Sim.pybullet and (scenario.endswith(".toml") or not Path(scenario).is_file()):
            scene = scenario
        else:
            specs.extend(parse_scenario(read_text(scenario), scenario))
    with Interrupts() as interrupted:  # a signal while the world opens stops before tick 1
        world, scene_agents = open_world(task, sim, scene, seed, gui, record,
                                         probabilities(fail_prob))
        deadline = None if timeout is None else time.monotonic() + timeout

        def stop() -> bool:
            return interrupted() or (deadline is not None and time.monotonic() > deadline)

        try:
            with RunFiles(trace, plan_out, world) as files:
                result = _act(task, world, specs, scene_agents, seed, max_ticks, rate, quiet,
                              files.add, stop, WORLD_NAMES[sim], extended, sim is not Sim.symbolic)
        finally:
            if hasattr(world, "close"):
                world.close()  # closes a recording into a playable file, interrupted or not
    if result.interrupted and not interrupted():
        result.reason = f"the time budget ({timeout:g} s) ran out"
    stderr.print(summary_table(result))
    if interrupted():
        raise typer.Exit(interrupted.exit_code)
    if not result.reached:
        stderr.print(f"[bold red]failed:[/] {escape(result.reason)}")
        raise typer.Exit(EXIT_FAILED)


WORLD_NAMES = {"symbolic": "the symbolic world", "pybullet": "the PyBullet world"}


class RunFiles:
    """The files that record a run in progress: the trace and the plan so far.

    Both are brought up to date after every tick, so an interrupted (or killed) run
    leaves what it did: the trace gets one line per tick, the plan file is replaced
    whenever an action finishes (on standard output, the new actions are appended).
    """

    def __init__(self, trace: str | None, plan_out: str | None, world: Any) -> None:
        self.trace = LineStream(trace) if trace is not None else None
        self.plan_out, self.world = plan_out, world
        self._done = 0

    def __enter__(self) -> Self:
        if self.trace is not None:
            self.trace.__enter__()
        if self.plan_out is not None and self.plan_out != STDIO:
            write_atomic(self.plan_out, "")
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self.trace is not None:
            self.trace.__exit__(kind, error, tb)

    def add(self, record: TickRecord) -> None:
        """The plan first, then the trace: an action the trace shows finished is in the
        plan file, even when the run is killed between the two writes."""
        self._write_plan()
        if self.trace is not None:
            self.trace.write_line(record.to_json())

    def _write_plan(self) -> None:
        executed = list(self.world.executed)
        if self.plan_out is None or len(executed) == self._done:
            return
        if self.plan_out == STDIO:
            sys.stdout.write("".join(a.ipc() + "\n" for a in executed[self._done:]))
            sys.stdout.flush()
        else:
            write_atomic(self.plan_out, "".join(a.ipc() + "\n" for a in executed))
        self._done = len(executed)


def _act(task: Task, world: Any, specs: list[DisturbSpec], scene_agents: list[Agent], seed: int,
         max_ticks: int, rate: float | None, quiet: bool, keep: Callable[[TickRecord], None],
         stop: Callable[[], bool], world_name: str, extended: bool, simulated: bool
         ) -> acting.RunOutcome:
    """Act, with the live view on a terminal, progress lines in a pipe, or nothing (-q)."""
    from btplan import acting
    from btplan.acting.extended import NONE, extended_options, extensions

    options = extended_options(stall_limit=max_ticks) if extended else None
    settings = extensions(simulated) if extended else NONE

    def run_with(view: Callable[[Node, Mapping[int, Status], TickRecord], None] | None
                 ) -> acting.RunOutcome:
        def each(root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
            keep(record)
            if view is not None:
                view(root, reached, record)

        return acting.run(task, disturb=specs, agents=scene_agents, world=world, seed=seed,
                          max_ticks=max_ticks, view=each, rate=rate, stop=stop,
                          world_name=world_name, options=options, **settings)

    if quiet:
        return run_with(None)
    if stderr.is_terminal:
        from btplan.acting.live_view import LiveView

        with LiveView(stderr.rich) as live:
            return run_with(live.show)
    return run_with(progress_line)


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


def summary_table(result: acting.RunOutcome) -> Table:
    """Outcome, ticks, expansions (and when), conflicts, actions, disturbances."""
    from rich.table import Table

    total = result.summary()
    table = Table(title="btplan run", show_header=False, box=None)
    table.add_column(style="bold")
    table.add_column(overflow="fold")
    if result.reached:
        outcome = "[green]goal reached[/]"
    elif result.interrupted and result.reason == "interrupted":
        outcome = "[yellow]interrupted[/] before the goal was reached"
    else:
        outcome = f"[red]not reached[/]: {escape(result.reason)}"
    table.add_row("outcome", outcome)
    table.add_row("ticks", str(total.ticks))
    grown = ", ".join(f"{e.condition} @{tick}" for tick, e in total.expansions)
    table.add_row("expansions", f"{len(total.expansions)}" + (f" ({escape(grown)})" if grown else ""))
    table.add_row("conflicts resolved", str(total.conflicts_resolved))
    table.add_row("executed", _listing(total.finished))
    table.add_row("halted", _listing(total.halted + list(result.halted_on_stop)))
    table.add_row("failed", _listing(total.failed))
    table.add_row("disturbances",
                  _listing([f"@{d.tick} {d.description}" for d in total.disturbances]))
    return table


def _listing(items: list[str]) -> str:
    return f"{len(items)}" + (f": {escape(', '.join(items))}" if items else "")
