"""The `btplan run` command: plan and act at once in a world, with external agents."""

from __future__ import annotations

import importlib
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from types import TracebackType
from typing import TYPE_CHECKING, Annotated, Any, Self

import typer

from btplan.cli.console import escape
from btplan.cli.interrupts import HardDeadline, Interrupts, TimeLimitReached
from btplan.cli.monitors import check_btlog, check_port, closing_monitors, open_monitors
from btplan.cli.outputs import LineStream, Output, check_outputs, write_atomic
from btplan.cli.typer_app import EXIT_FAILED, app, guarded, stderr
from btplan.errors import InputError, Interrupted, Span, WorldError
from btplan.io import read_text, stream_of, write_stream

if TYPE_CHECKING:
    from rich.table import Table

    from btplan import acting
    from btplan.acting.records import TickRecord
    from btplan.bt import Node, Status
    from btplan.model import Task
    from btplan.worlds.agents import Agent
    from btplan.monitor.run_monitor import RunMonitor, TickUpdate
    from btplan.worlds.disturb import DisturbSpec


class Sim(str, Enum):
    """The world `btplan run --sim` acts in: the symbolic one, or PyBullet (an extra,
    imported only when chosen)."""
    symbolic = "symbolic"
    pybullet = "pybullet"


EXAMPLES = """Examples:

  btplan run domains/pick_place.bt --disturb undo:Pick@5 --rate 4
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist --paper
  btplan run domains/pick_place.bt --world examples/my_robot.py:FetchRobot --hz 10
  btplan run domains/pick_place_obstacle.bt --ros examples/ros/example2.toml --hz 10
  btplan run domains/pick_place.bt --keep --disturb 'undo:Place@p=0.05' --max-ticks 500
  btplan run domains/youbot.bt --sim pybullet -q --trace run.jsonl --plan-out p.plan
  btplan run domains/pick_place.bt --plan-out - | wc -l
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist --groot --hz 2
  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist --btlog run.btlog
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
    max_ticks: Annotated[int | None, typer.Option(
        "--max-ticks", min=1, metavar="N",
        help="Give up after N ticks (exit 1). Default 1000, or no limit with --keep.",
        show_default=False)] = None,
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
    hz: Annotated[float | None, typer.Option(
        "--hz", "--rate", min=0.01, metavar="HZ",
        help="Tick at this fixed rate on the wall clock, as a robot's tree does (default: "
             "as fast as possible). Skills are polled, never waited for; ticks that start "
             "late are counted in the summary.")] = None,
    keep: Annotated[bool, typer.Option(
        "--keep",
        help="Keep ticking after the goal is reached, as Algorithm 1 does: a goal an agent "
             "undoes is achieved again. Runs until Ctrl-C, --timeout or --max-ticks "
             "(no tick limit unless given).")] = False,
    quiet: Annotated[bool, typer.Option(
        "-q", "--quiet", help="No live view and no progress; the summary only.")] = False,
    paper: Annotated[bool, typer.Option(
        "--paper",
        help="Algorithm 1 exactly as published: one expansion per tick, first-match "
             "achievers, no departure, and the run ends after a few failing ticks. Without "
             "it, the default preset (docs/robot.md): the task is planned as `btplan plan` "
             "plans it before the first action, the tree grows within the tick until it "
             "runs, a failing skill is retried, and the departures of docs/design/acting.md "
             "act.")] = False,
    preset: Annotated[str | None, typer.Option(
        "--preset", metavar="NAME",
        help="How the loop acts, by preset: paper (as --paper), algorithm1 (Algorithm 1's "
             "loop with btplan's ranking of achievers), default, simulator (the default "
             "in PyBullet). Default: default, or simulator in PyBullet.",
        show_default=False)] = None,
    world_spec: Annotated[str | None, typer.Option(
        "--world", metavar="FILE.py:CLASS",
        help="Act in your own robot: a class (or factory) in a Python file or module, "
             "e.g. my_robot.py:Robot or my_package.robot:Robot, called with the task "
             "(see docs/robot.md).", show_default=False)] = None,
    ros: Annotated[str | None, typer.Option(
        "--ros", metavar="FILE.toml",
        help="Act on a ROS 2 robot: its action servers and topics, as the binding file "
             "maps them (docs/ros.md). Needs ROS 2 for Python: pip install 'btplan[ros]'.",
        show_default=False)] = None,
    gui: Annotated[bool, typer.Option(
        "--gui", help="Open the PyBullet window (--sim pybullet).")] = False,
    record: Annotated[str | None, typer.Option(
        "--record", metavar="FILE.gif", help="Record the PyBullet run to a GIF (--sim pybullet).")
    ] = None,
    groot: Annotated[int | None, typer.Option(
        "--groot", metavar="[PORT]",
        help="Serve the growing tree to Groot2 (BehaviorTree.CPP's monitor protocol) on "
             "127.0.0.1:PORT and PORT+1; PORT defaults to 1667. Connect Groot2's monitor "
             "to this machine and port (docs/monitor.md).", show_default=False)] = None,
    view: Annotated[int | None, typer.Option(
        "--view", metavar="[PORT]",
        help="Show the run in the browser as it goes, at http://127.0.0.1:PORT/ (default "
             "8765; 0: a free port): the tree, coloured by status, with a timeline to "
             "scrub back. The page keeps the ticks it has once the run ends; `btplan "
             "view` shows a saved --trace again.", show_default=False)] = None,
    btlog: Annotated[str | None, typer.Option(
        "--btlog", metavar="FILE.btlog",
        help="Write the run as a Groot2 replay file (BehaviorTree.CPP's FileLogger2 "
             "format), put together when the run ends, however it ends.",
        show_default=False)] = None,
    goal: Annotated[str | None, typer.Option(
        "--goal", metavar="CONDITION", show_default=False,
        help="Act toward this goal instead of the problem's, from the same objects and "
             "initial state: one PDDL condition, such as '(and (on a b) (clear c))'.")] = None,
) -> None:
    """Run Algorithm 1 online: tick the tree, expand it when it fails, let agents disturb it.

    Exit 0 when the goal is reached, 1 when it is not within --max-ticks or --timeout,
    2 on bad input. Ctrl-C (or SIGTERM) stops at the next tick: the running action is
    halted, the trace and the plan keep every finished tick, the summary is printed,
    and the exit code is 130 (143).
    """
    started = time.monotonic()  # the time limit counts from here
    # The acting layer and the worlds are imported here: every command's module is
    # imported when btplan starts, and only this command (and sweep) acts.
    from btplan import acting
    from btplan.shipped import resolve
    from btplan.worlds.disturb import parse_scenario, parse_spec

    if timeout is not None and timeout <= 0:
        raise InputError(f"--timeout must be positive, got {timeout:g}")
    if max_ticks is None:
        max_ticks = None if keep else 1000
    if paper and preset not in (None, "paper"):
        raise InputError("--paper and --preset name two presets; give one",
                         Span("--preset", 1, 1))
    from btplan.acting.config import PRESETS

    if preset is not None and preset not in PRESETS:
        raise InputError(f"no preset named {preset!r}", Span("--preset", 1, 1),
                         f"presets: {', '.join(PRESETS)}")
    check_port("--groot", groot)
    if view is not None and not 0 <= view <= 65535:
        raise InputError(f"--view {view}: a port is a number from 0 to 65535",
                         Span("--view", 1, 1))
    check_btlog(btlog)
    check_outputs(Output("--trace", trace), Output("--plan-out", plan_out),
                  Output("--record", record), Output("--btlog", btlog),
                  inputs=[domain, *(p for p in (problem, scenario) if p),
                          *([world_spec.rpartition(":")[0]] if world_spec else []),
                          *([ros] if ros else [])])
    task = acting.load(resolve(domain), *([problem] if problem is not None else []))
    if goal is not None:
        from btplan.lang import with_goal

        task = with_goal(task, goal, source="--goal")
    specs = [parse_spec(text, Span("--disturb", 1, 1)) for text in disturb or []]
    scene: str | None = None
    if scenario is not None:
        if sim is Sim.pybullet and (scenario.endswith(".toml") or not Path(scenario).is_file()):
            scene = scenario
        else:
            specs.extend(parse_scenario(read_text(scenario), scenario))
    with Interrupts() as interrupted:  # a signal while the world opens stops before tick 1
        if ros is not None:
            from btplan.cli.ros_world import open_ros_robot

            if world_spec is not None or sim is not Sim.symbolic or gui or record or fail_prob:
                raise InputError("--ros cannot be combined with --world, --sim, --gui, "
                                 "--record or --fail-prob", Span("--ros", 1, 1))
            world, scene_agents = open_ros_robot(ros, task), list[Any]()
        elif world_spec is not None:
            from btplan.cli.user_world import open_user_world

            if sim is not Sim.symbolic or gui or record or fail_prob:
                raise InputError("--world cannot be combined with --sim, --gui, --record "
                                 "or --fail-prob", Span("--world", 1, 1))
            world, scene_agents = open_user_world(world_spec, task), list[Any]()
        else:
            world, scene_agents = open_world(task, sim, scene, seed, gui, record,
                                             probabilities(fail_prob))
        # counted from the start of the command, as plan's: opening the world included
        deadline = None if timeout is None else started + timeout

        files = RunFiles(trace, plan_out, interrupted)

        def stop() -> bool:
            return (interrupted() or files.failed is not None
                    or (deadline is not None and time.monotonic() > deadline))

        settings = Acting(seed=seed, max_ticks=max_ticks, rate=hz, keep=keep,
                          preset="paper" if paper else preset, quiet=quiet,
                          world_name=(f"the ROS 2 robot of {ros}" if ros is not None
                                      else WORLD_NAMES[sim] if world_spec is None
                                      else world_spec))
        try:
            watch = open_monitors(groot, btlog, view, world, domain,
                                  [m for m in [world.tree_topics()] if m is not None]
                                  if ros is not None else [])
            # The run stops itself at the tick after the budget; the timer is for a tick
            # that does not end (a long expansion): skills are halted on the way out.
            with files, closing_monitors(watch), HardDeadline(timeout, started,
                                                               grace=TICK_GRACE):
                result = _act(task, world, specs, scene_agents, settings, files.add, stop,
                              watch)
        except TimeLimitReached:
            stderr.print(f"[bold red]failed:[/] the time budget ({timeout:g} s) ran out in "
                         "the middle of a tick; the running skills were halted")
            raise typer.Exit(EXIT_FAILED) from None
        except Interrupted as stopped:  # a signal while the trace pipe had no reader
            stderr.print(f"[bold yellow]interrupted[/] {escape(stopped.progress)}")
            raise typer.Exit(interrupted.exit_code) from None
        finally:
            from btplan.robot.contract import capabilities_of

            if capabilities_of(world).closes:
                world.close()  # closes a recording into a playable file, interrupted or not
    if files.failed is not None:
        result.reason = "an output could not be written"
    elif result.interrupted and not interrupted():
        result.reason = f"the time budget ({timeout:g} s) ran out"
    stderr.print(summary_table(result))
    if files.failed is not None:
        raise files.failed
    if interrupted():
        raise typer.Exit(interrupted.exit_code)
    if not result.reached:
        stderr.print(f"[bold red]failed:[/] {escape(result.reason)}")
        raise typer.Exit(EXIT_FAILED)


WORLD_NAMES = {"symbolic": "the symbolic world", "pybullet": "the PyBullet world"}

TICK_GRACE = 0.4
"""Seconds past --timeout before a tick that has not ended is cut short."""


class RunFiles:
    """The files that record a run in progress: the trace and the plan so far.

    Both are brought up to date after every tick, so an interrupted (or killed) run
    leaves what it did: the trace gets one line per tick, the plan file is replaced
    whenever an action finishes (on standard output, the new actions are appended).
    """

    def __init__(self, trace: str | None, plan_out: str | None,
                 stop: Callable[[], bool] | None = None) -> None:
        self.trace = LineStream(trace, stop) if trace is not None else None
        self.plan_out = plan_out
        self._lines: list[str] = []
        self.failed: InputError | None = None
        """Why an output could not be written (a full disk): the run stops at the next
        tick, with its summary, and the command exits 2 with this."""

    def __enter__(self) -> Self:
        if self.trace is not None:
            self.trace.__enter__()
        if self.plan_out is not None and stream_of(self.plan_out) is None:
            write_atomic(self.plan_out, "")
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self.trace is not None:
            self.trace.__exit__(kind, error, tb)

    def add(self, update: TickUpdate) -> None:
        """The plan first, then the trace: an action the trace shows finished is in the
        plan file, even when the run is killed between the two writes. An output that
        cannot be written any more is not written again (`failed`)."""
        if self.failed is not None:
            return
        flag, path = "--plan-out", self.plan_out
        try:
            self._write_plan(update.record.plan_lines)
            if self.trace is not None:
                flag, path = "--trace", self.trace.path
                self.trace.write_line(update.line)
        except OSError as error:
            self.failed = InputError(f"{flag} {path}: cannot write: "
                                     f"{error.strerror or error}; the run stopped there")

    def _write_plan(self, new: tuple[str, ...]) -> None:
        if self.plan_out is None or not new:
            return
        self._lines.extend(line + "\n" for line in new)
        stream = stream_of(self.plan_out)
        if stream is not None:  # a stream takes the new lines; a file is written whole
            write_stream(stream, "".join(line + "\n" for line in new))
        else:
            write_atomic(self.plan_out, "".join(self._lines))


@dataclass(frozen=True)
class Acting:
    """The run's settings from the command line, as `_act` passes them on."""

    seed: int
    max_ticks: int | None
    rate: float | None
    keep: bool
    preset: str | None
    quiet: bool
    world_name: str


def _act(task: Task, world: Any, specs: list[DisturbSpec], scene_agents: list[Agent],
         settings: Acting, keep: Callable[[TickUpdate], None], stop: Callable[[], bool],
         watch: RunMonitor) -> acting.RunOutcome:
    """Act, with the live view on a terminal, progress lines in a pipe, or nothing (-q)."""
    from btplan import acting
    from btplan.acting.config import ActingConfig

    # None: the world's default (btplan.acting.online.default_config)
    config = ActingConfig.preset(settings.preset) if settings.preset else None

    def run_with(view: Callable[[Node, Mapping[int, Status], TickRecord], None] | None
                 ) -> acting.RunOutcome:
        def each(root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
            keep(watch.update(root, reached, record))
            if view is not None:
                view(root, reached, record)

        return acting.run(task, disturb=specs, agents=scene_agents, world=world,
                          seed=settings.seed, max_ticks=settings.max_ticks, view=each,
                          rate=settings.rate, keep=settings.keep, stop=stop,
                          world_name=settings.world_name, config=config)

    if settings.quiet:
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
    if result.reached and result.interrupted:
        outcome = "[green]goal holding[/] when the run was stopped"
    elif result.reached:
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
    table.add_row("executed", _listing(total.finished, total.count("finished")))
    if total.observed:
        table.add_row("  effects observed", _listing(total.observed, total.count("observed")))
    on_stop = list(result.halted_on_stop)  # running when the run ended, halted then
    table.add_row("halted", _listing(total.halted + on_stop,
                                     total.count("halted") + len(on_stop)))
    if total.unstopped:
        table.add_row("[red]did not stop[/]", _listing(total.unstopped))
    table.add_row("failed", _listing(total.failed, total.count("failed")))
    if total.errors:
        table.add_row("skill errors", _listing([f"{what}: {why}" for what, why in total.errors],
                                               total.count("errors")))
    table.add_row("disturbances",
                  _listing([f"@{d.tick} {d.description}" for d in total.disturbances],
                           total.count("disturbances")))
    if total.goal_reached and (len(total.goal_reached) > 1 or total.goal_lost):
        table.add_row("goal reached at", ", ".join(f"@{t}" for t in total.goal_reached))
        table.add_row("goal lost at", ", ".join(f"@{t}" for t in total.goal_lost) or "never")
    if total.overruns:
        worst = total.worst_lateness * 1000
        table.add_row("late ticks", f"{total.overruns} (worst {worst:.1f} ms)")
    return table


LISTED = 40
"""Names a summary row lists before it only counts."""


def _listing(items: list[str], count: int | None = None) -> str:
    total = len(items) if count is None else count
    shown = items[:LISTED]
    more = f", ... {total - len(shown)} more" if total > len(shown) else ""
    return f"{total}" + (f": {escape(', '.join(shown))}{more}" if shown else "")
