"""One acting run: a world, its external agents, the blended loop, and a record per tick.

This is what `btplan run` and `btplan.run` do: Algorithm 1 online, with agents
changing the world between ticks, at a fixed rate if asked, for as long as asked. It
only observes the loop (a tick recorder on the tree, the loop's skill events, the facts
before and after), so a run with a trace behaves exactly like one without.

Every way out of a run (the goal, the tick limit, a stop request, a planning error, an
exception from the world, KeyboardInterrupt, SIGTERM) halts every running skill and
waits a bounded time for them (btplan.acting.skills); skills that did not stop are
named in the outcome.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from btplan.acting.clock import Clock
from btplan.acting.config import ACTING_PLANNER, ActingConfig
from btplan.acting.diagnosis import world_says
from btplan.acting.loop import BlendedLoop
from btplan.acting.offline_turns import OfflineTurns
from btplan.acting.pacing import Pacer, Stop
from btplan.acting.recorder import Recorder, TickView
from btplan.acting.records import RunSummary, TickRecord
from btplan.acting.state import TickReport
from btplan.acting.stuck_wait import StuckWait
from btplan.bt import FAILURE, SUCCESS, BehaviorTree
from btplan.errors import PlanningError, SkillError
from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.records import field, record, replace
from btplan.robot.contract import capabilities_of
from btplan.worlds.agents import Agent, agents_from_specs, check_world
from btplan.worlds.disturb import DisturbSpec, check_specs, parse_spec
from btplan.worlds.symbolic import SymbolicWorld

__all__ = ["ACTING_OPTIONS", "RECENT_TICKS", "RunOutcome", "TickView", "run", "run_task",
           "task_models"]

ACTING_OPTIONS = ACTING_PLANNER
"""The planner's options while acting (btplan.acting.config.ACTING_PLANNER)."""

RECENT_TICKS = 10_000
"""Tick records an outcome keeps (the last ones); the summary counts every tick and
the trace streams every record, so a long run's memory stays flat."""


@record(slots=True)
class RunOutcome:
    """How a run ended, its summary, and the records of its last RECENT_TICKS ticks."""

    reached: bool
    reason: str
    tree: BehaviorTree
    world: Any
    records: list[TickRecord] = field(default_factory=list)
    interrupted: bool = False
    halted_on_stop: tuple[str, ...] = ()
    """The actions that were running when the run ended, and were halted then."""
    executed: list[GroundAction] = field(default_factory=list)
    """The grounded actions the robot completed, in order (what `--plan-out` writes)."""
    totals: RunSummary = field(default_factory=RunSummary)

    @property
    def ticks(self) -> int:
        """Ticks the run made."""
        return self.totals.ticks

    @property
    def unstopped(self) -> list[str]:
        """Skills that did not report stopping within the wait after they were halted."""
        return self.totals.unstopped

    def summary(self) -> RunSummary:
        """The totals over every tick (what `btplan run` prints)."""
        return self.totals

    def plan_text(self) -> str:
        """The executed actions in the IPC plan format, one per line."""
        return "".join(a.ipc() + "\n" for a in self.executed)


def task_models(task: Task, options: PlannerOptions | None = None) -> AchieverIndex:
    """What the loop's expansions use that depends on the task only, built now.

    The relaxed model (every grounding the static facts allow, for h_add) and, when
    the options use them, the h^2 mutexes: without this the first expansion of a run
    builds them, and its cost is not that of coping with the world.
    """
    models = AchieverIndex(task, options or ACTING_OPTIONS)
    models.relaxed.actions  # noqa: B018 (built on first access)
    if (options or ACTING_OPTIONS).mutexes:
        models.mutexes.ready()
    return models


def default_config(world: object | None) -> ActingConfig:
    """The preset for a world: `simulator` for one that refines values as it runs
    (it declares `continuous`), `default` otherwise."""
    simulated = world is not None and capabilities_of(world).continuous
    return ActingConfig.simulator() if simulated else ActingConfig.default()


class Terminated(BaseException):
    """SIGTERM arrived during a run started outside btplan's CLI: halt, then exit."""


@contextmanager
def _terminate_cleanly() -> Iterator[None]:
    """In the main thread, with SIGTERM left at its default (which kills the process at
    once), turn it into Terminated for the duration of the run, so that skills are
    halted first. A program that handles SIGTERM itself keeps its own handler."""
    import signal
    import threading

    if (threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL):
        yield
        return

    def handle(signum: int, frame: object) -> None:
        raise Terminated

    signal.signal(signal.SIGTERM, handle)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def run_task(
    task: Task,
    *,
    world: Any | None = None,
    agents: Sequence[Agent] = (),
    config: ActingConfig | None = None,
    seed: int = 0,
    max_ticks: int | None = 1000,
    rate: float | None = None,
    keep: bool = False,
    view: TickView | None = None,
    stop: Callable[[], bool] | None = None,
    clock: Clock | None = None,
    models: AchieverIndex | None = None,
) -> RunOutcome:
    """Plan and act at once (Algorithm 1) in `world`, with `agents` acting before each tick.

    Without a world, the symbolic one is used, seeded with `seed`. The loop never
    rebuilds the tree: it only grows on FAILURE, as the paper's Problem 1 asks. See
    `run` for the arguments.
    """
    if world is None:
        world = SymbolicWorld(task, seed=seed)
    config = config or default_config(world)
    options = replace(config.loop_planner, stall_limit=config.stall_limit(max_ticks))
    loop = BlendedLoop(task, world, options, like=models, config=config)
    pacer = Pacer(rate, clock, stop)
    recorder = Recorder(loop, world, agents, view, deque(maxlen=RECENT_TICKS))
    offline = OfflineTurns(task, config, world, stop)
    reached, reason, interrupted, raised = False, "", False, None
    try:
        with _terminate_cleanly():
            try:
                stuck = StuckWait(config.stuck_wait, pacer.clock if pacer.period else None)
                reached, reason = _drive(loop, pacer, recorder, max_ticks, keep, offline, stuck)
            except Stop:
                reason, interrupted = "interrupted", True
                if keep and recorder.goal_held:  # a kept run stopped with the goal holding
                    reached, reason = True, "interrupted with the goal holding"
            except (PlanningError, SkillError) as error:
                # The tree cannot grow any further (no achiever, going round in circles),
                # or a skill raised and the run stops on it: the run ends as not reached,
                # and its records, this last tick included, tell why.
                reason = (error.reason + world_says(loop.skills)
                          if isinstance(error, PlanningError) else str(error))
                recorder.close_tick()
            except BaseException as error:  # KeyboardInterrupt, SIGTERM, a world's bug
                raised = error
            finally:
                halted, unstopped = _halt_everything(loop, config, clock)
    finally:
        recorder.detach()
    recorder.summary.end(unstopped, pacer.overruns, pacer.worst_lateness)
    if raised is not None:
        if isinstance(raised, Terminated):
            raise SystemExit(143) from None
        raise raised
    return RunOutcome(reached=reached, reason=reason, tree=loop.tree, world=world,
                      records=list(recorder.kept), interrupted=interrupted,
                      halted_on_stop=halted, executed=list(loop.skills.executed),
                      totals=recorder.summary)


def _drive(loop: BlendedLoop, pacer: Pacer, recorder: Recorder, max_ticks: int | None,
           keep: bool, offline: OfflineTurns, stuck: StuckWait) -> tuple[bool, str]:
    """Tick until the goal is reached (with `keep`, on until the limit), or the limit.

    When the loop gets stuck, a paced run ticks on for a while first (`stuck`); then
    the tree planned offline from the facts of now takes over, if any.

    The goal is checked in the world after the tick: when actions finish within the
    tick they start in, later work may undo a goal checked earlier in the same tick,
    and the next tick must then put it right.
    """
    ticks = 0
    held = False
    while max_ticks is None or ticks < max_ticks:
        pacer.wait()
        recorder.before(loop.ticks + 1)
        ahead = offline.ahead(loop) if ticks == 0 else None
        try:
            report = loop.tick()
            if ahead is not None:
                report.follows(ahead)
            stuck.after(report.status)
        except PlanningError as error:
            if stuck.holds(error):
                report = TickReport(loop.ticks, FAILURE)  # the dead end may pass: wait
            else:
                taken = offline.take_over(loop)
                if taken is None:
                    raise
                report = taken  # the loop acts on the tree planned offline from the next tick
        ticks += 1
        now = report.status is SUCCESS and loop.goal_holds()
        goal = "reached" if now and not held else "lost" if held and not now else ""
        held = now
        recorder.after(report, goal, now)
        if now and not keep:
            return True, "goal reached"
    if keep and held:
        return True, f"the goal held at the last of {ticks} ticks"
    return False, f"the goal was not reached within {ticks} ticks{world_says(loop.skills)}"


def _halt_everything(loop: BlendedLoop, config: ActingConfig,
                     clock: Clock | None) -> tuple[tuple[str, ...], list[str]]:
    """Halt the tree and every running skill; the names of those halted, and of those
    that did not stop within the wait."""
    try:
        loop.tree.halt(loop.skills)
    except Exception:  # noqa: BLE001 (a node's halt failed: the skills are halted below)
        pass
    unstopped = loop.skills.halt_all(config.halt_wait, clock)
    events = loop.skills.take_events()
    halted = tuple(str(a) for a in (*events.halted, *events.observed))
    return halted, unstopped


def run(
    task: Task,
    *,
    world: Any | None = None,
    config: ActingConfig | None = None,
    disturb: Sequence[str | DisturbSpec] = (),
    agents: Sequence[Agent] = (),
    seed: int = 0,
    max_ticks: int | None = 1000,
    rate: float | None = None,
    keep: bool = False,
    view: TickView | None = None,
    stop: Callable[[], bool] | None = None,
    clock: Clock | None = None,
    models: AchieverIndex | None = None,
    world_name: str = "this world",
) -> RunOutcome:
    """Plan and act in a world (the library form of `btplan run`); docs/robot.md.

    - `world`: any object with the calls of btplan.robot.World (a `btplan.robot.Robot`,
      the PyBullet world, your own); by default the symbolic world, seeded with `seed`.
    - `config`: an ActingConfig (`ActingConfig.paper()` for Algorithm 1 as published);
      by default `default`, or `simulator` for a world that declares `continuous`.
    - `disturb`: specs such as `"undo@5"` or `"set:blocked(tau_goal)@p=0.05"` (syntax in
      docs/cli.md), checked against the task first; `agents`: any other agents (a
      simulator's scripted events), acting before each tick.
    - `max_ticks`: the tick limit (None: none); `rate`: ticks per second on `clock`
      (the system's monotonic clock by default; tests pass a FakeClock); `keep`: tick
      on after the goal is reached, as Algorithm 1 does, so that a goal undone is
      achieved again, until the limit or a stop.
    - `view`: called after every tick with the tree, the statuses and the tick's record;
      `stop`: asked before every tick (and while waiting) whether to end the run there.
    - `models`: the task's models built beforehand (`task_models`), so that their cost
      can be told apart from the expansions'; `world_name`: how messages name the world.

    Returns the outcome (its summary counts every tick); raises InputError for a bad
    spec. KeyboardInterrupt and SIGTERM halt every running skill before they end the
    program.

    An agent takes the cube out of the gripper at tick 5: the tree picks it again,
    with no new expansion (the first reactive property).

        >>> from btplan.acting.offline.planning import load
        >>> outcome = run(load("pick_place"), disturb=["undo:Pick@5"])
        >>> outcome.reached, outcome.reason
        (True, 'goal reached')
        >>> [str(action) for action in outcome.executed][:3]
        ['MoveTo(cube, tau_cube)', 'Pick(cube)', 'Pick(cube)']
        >>> [tick for tick, _ in outcome.totals.expansions]
        [1, 1, 1, 1]
    """
    specs = [parse_spec(s) if isinstance(s, str) else s for s in disturb]
    check_specs(specs, task)
    if world is not None:
        check_world(specs, world, world_name)
        from btplan.robot.api import Robot

        if isinstance(world, Robot):  # checked against the domain before tick 1
            world.bind(task)
    everyone = [*agents_from_specs(specs, seed), *agents]
    return run_task(task, world=world, agents=everyone, config=config, seed=seed,
                    max_ticks=max_ticks, rate=rate, keep=keep, view=view, stop=stop,
                    clock=clock, models=models)

