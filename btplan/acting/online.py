"""One acting run: a world, its external agents, the blended loop, and a record per tick.

This is what `btplan run` and `btplan.run` do: Algorithm 1 online, with agents
changing the world between ticks. It only observes the loop (a tick recorder on the
tree, the world's action logs, the facts before and after), so a run with a trace
behaves exactly like one without.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from btplan.acting.loop import BlendedLoop, Expansion, TickReport
from btplan.acting.records import ExpansionNote, RunSummary, TickRecord, summarize
from btplan.bt import FAILURE, BehaviorTree, Node, Status
from btplan.bt.trace import TickRecorder
from btplan.errors import PlanningError
from btplan.model import Atom, GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.records import field, record
from btplan.worlds.agents import Agent, act_all, agents_from_specs, check_world
from btplan.worlds.disturb import DisturbSpec, check_specs, parse_spec
from btplan.worlds.symbolic import SymbolicWorld

TickView = Callable[[Node, Mapping[int, Status], TickRecord], None]
"""Called after every tick with the tree, id(node) -> status for the nodes this tick
reached, and the tick's record: the live view is one."""

_LOGS = ("started", "halted", "executed", "failed")

ACTING_OPTIONS = PlannerOptions(closest_first=False)
"""The planner's defaults while acting, less nearest-first expansion.

Breadth-first choice of the condition to expand (the paper's Algorithm 3) grows the
shallow alternatives of a Fallback before the deep ones, so an agent that undoes an
action often finds the other way to redo it already in the tree: no new expansion, as
Problem 1 asks. Nearest-first reaches a long plan in far fewer expansions, which is what
offline planning (`plan`) needs, but it leaves those alternatives unexpanded."""


@record(slots=True)
class RunOutcome:
    """How a run ended, and everything that happened on the way (one record per tick)."""

    reached: bool
    reason: str
    tree: BehaviorTree
    world: Any
    records: list[TickRecord] = field(default_factory=list)
    interrupted: bool = False
    halted_on_stop: tuple[str, ...] = ()
    """The actions that were running when the run was interrupted, and were halted."""

    @property
    def ticks(self) -> int:
        return len(self.records)

    @property
    def executed(self) -> list[GroundAction]:
        """The grounded actions the robot completed, in order (what `--plan-out` writes)."""
        return list(self.world.executed)

    def summary(self) -> RunSummary:
        return summarize(self.records)

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
        models.mutexes  # noqa: B018
    return models


class _Observer:
    """Turns what the loop and the world did around one tick into a TickRecord."""

    def __init__(self, world: Any, agents: Sequence[Agent], tree: BehaviorTree,
                 view: TickView | None, rate: float | None,
                 stop: Callable[[], bool] | None = None) -> None:
        self.world, self.agents, self.tree, self.view = world, list(agents), tree, view
        self.stop = stop
        self.period = 1.0 / rate if rate else 0.0
        self.recorder = TickRecorder()
        self.recorder.attach(tree)
        self.records: list[TickRecord] = []
        self._facts: frozenset[Atom] = world.facts()
        self._marks: dict[str, int] = {}
        self._ids: dict[str, Node] = {}
        self._disturbances: list[Any] = []
        self._next = time.monotonic()

    def before(self, tick: int) -> None:
        """Pace the run, let the agents act, and remember where the logs stood."""
        if self.period:
            # in short naps, so that a stop request does not wait for a slow rate
            while (delay := self._next - time.monotonic()) > 0:
                if self.stop is not None and self.stop():
                    break
                time.sleep(min(delay, 0.05))
            self._next = max(self._next, time.monotonic()) + self.period
        if self.stop is not None and self.stop():
            raise _Stop
        self._marks = {name: len(getattr(self.world, name)) for name in _LOGS}
        self._disturbances = act_all(self.agents, self.world, tick)
        self._ids = {f"n{i}": node for i, node in enumerate(self.tree.nodes())}

    def after(self, report: TickReport) -> None:
        traces = list(self.recorder.traces)
        self.recorder.traces.clear()
        nodes = traces[-1].nodes if traces else ()
        if len(traces) > 1:  # the tree grew and was ticked again within this tick
            self._ids = {f"n{i}": node for i, node in enumerate(self.tree.nodes())}
        reached = {id(self._ids[n.id]): n.status for n in nodes if n.id in self._ids}
        facts = self.world.facts()
        record = TickRecord(
            tick=report.tick,
            status=report.status.value,
            nodes=nodes,
            started=self._since("started"),
            halted=self._since("halted"),
            finished=self._since("executed"),
            failed=self._since("failed"),
            disturbances=tuple(self._disturbances),
            expansions=tuple(note(e) for e in report.expansions),
            added=tuple(str(a) for a in sorted(facts - self._facts)),
            removed=tuple(str(a) for a in sorted(self._facts - facts)),
            planning_seconds=report.planning_seconds,
            checks=sum(1 for t in traces for n in t.nodes if n.kind == "Condition")
            + report.checks_ahead,
        )
        self._facts = facts
        self.records.append(record)
        if self.view is not None:
            self.view(self.tree.root, reached, record)

    def _since(self, log: str) -> tuple[str, ...]:
        return tuple(str(a) for a in getattr(self.world, log)[self._marks.get(log, 0):])


class _Stop(Exception):
    """Raised between ticks when the caller asks the run to stop."""


def note(expansion: Expansion) -> ExpansionNote:
    """An expansion as the trace shows it: the condition, its achievers, the moves made."""
    return ExpansionNote(
        condition=str(expansion.condition),
        achievers=tuple(str(a) for a in expansion.achievers),
        conflicts_resolved=int(expansion.conflicts_resolved),
        moves=int(expansion.moves),
    )


def run_task(
    task: Task,
    *,
    world: Any | None = None,
    agents: Sequence[Agent] = (),
    seed: int = 0,
    max_ticks: int = 1000,
    view: TickView | None = None,
    rate: float | None = None,
    failure_probability: Mapping[str, float] | None = None,
    options: PlannerOptions | None = None,
    stop: Callable[[], bool] | None = None,
    look_ahead: bool = False,
    models: AchieverIndex | None = None,
    scope_moves: bool = False,
    goal_credit: bool = False,
    finish_first: bool = False,
    look_deeper: bool = False,
) -> RunOutcome:
    """Plan and act at once (Algorithm 1) in `world`, with `agents` acting before each tick.

    Without a world, the symbolic one is used, seeded with `seed`. The loop never
    rebuilds the tree: it only grows on FAILURE, as the paper's Problem 1 asks.
    `stop` is asked before every tick; when it says yes, the tree is halted (the
    world stops what the robot was doing) and the outcome is marked interrupted.
    """
    if world is None:
        world = SymbolicWorld(task, seed=seed, failure_probability=failure_probability)
    loop = BlendedLoop(task, world, options or ACTING_OPTIONS, like=models,
                       look_ahead=look_ahead, scope_moves=scope_moves,
                       goal_credit=goal_credit, finish_first=finish_first,
                       look_deeper=look_deeper)
    observer = _Observer(world, agents, loop.tree, view, rate, stop)
    interrupted = False
    halted_on_stop: tuple[str, ...] = ()
    try:
        outcome = loop.run(max_ticks, before_tick=observer.before, on_tick=observer.after)
        reached, reason = outcome.reached, outcome.reason
    except _Stop:
        reached, reason, interrupted = False, "interrupted", True
        mark = len(world.halted) if hasattr(world, "halted") else 0
        loop.tree.halt(world)
        halted_on_stop = tuple(str(a) for a in getattr(world, "halted", [])[mark:])
    except PlanningError as error:
        # The tree cannot grow any further (no achiever, going round in circles): the run
        # ends as not reached, and its records, this last tick included, tell why.
        reached, reason = False, error.reason
        if not observer.records or observer.records[-1].tick != loop.ticks:
            observer.after(TickReport(loop.ticks, FAILURE))
    finally:
        observer.recorder.detach(loop.tree)
    return RunOutcome(reached=reached, reason=reason, tree=loop.tree, world=world,
                      records=observer.records, interrupted=interrupted,
                      halted_on_stop=halted_on_stop)


def run(
    task: Task,
    *,
    disturb: Sequence[str | DisturbSpec] = (),
    agents: Sequence[Agent] = (),
    world: Any | None = None,
    seed: int = 0,
    max_ticks: int = 1000,
    view: TickView | None = None,
    rate: float | None = None,
    failure_probability: Mapping[str, float] | None = None,
    options: PlannerOptions | None = None,
    stop: Callable[[], bool] | None = None,
    world_name: str = "this world",
    look_ahead: bool = False,
    models: AchieverIndex | None = None,
    scope_moves: bool = False,
    goal_credit: bool = False,
    finish_first: bool = False,
    look_deeper: bool = False,
) -> RunOutcome:
    """Run `task` in a world with disturbances: the library form of `btplan run`.

    `disturb` holds specs such as `"undo@5"` or `"set:blocked(tau_goal)@p=0.05"`
    (syntax in docs/cli.md), checked against the task first; `agents` are any other
    agents (a simulator's scripted events). Returns the outcome with one record per
    tick; raises InputError for a bad spec. `options` are the planner's
    (`PlannerOptions.paper()` for the published algorithms); `stop` is asked before
    each tick whether to end the run there (see `run_task`); `world_name` is how
    messages call the world ("the PyBullet world"); `look_ahead` expands the later
    false preconditions of an action with the first (btplan.acting.ahead), and a
    condition ahead of the running action as soon as an agent breaks it
    (btplan.acting.watch); `scope_moves`
    skips a subtree moved out of an achiever while that achiever's condition holds
    (btplan.acting.scope); `goal_credit` ranks first the achievers that make other
    goals true and sets up the step of another goal an achiever enables
    (btplan.acting.credit, btplan.acting.prepare); `finish_first` finishes a halted
    action that does not interfere with the one started instead (btplan.acting.finish);
    `look_deeper`, without `look_ahead`, expands a later false precondition early only
    when its achiever needs something that would make the robot give up what it is
    about to hold (btplan.acting.ahead); `models`
    are the task's models built beforehand (`task_models`), so that their cost can
    be told apart from the expansions'.
    """
    specs = [parse_spec(s) if isinstance(s, str) else s for s in disturb]
    check_specs(specs, task)
    if world is not None:
        check_world(specs, world, world_name)
    everyone = [*agents_from_specs(specs, seed), *agents]
    return run_task(task, world=world, agents=everyone, seed=seed, max_ticks=max_ticks,
                    view=view, rate=rate, failure_probability=failure_probability,
                    options=options, stop=stop, look_ahead=look_ahead, models=models,
                    scope_moves=scope_moves, goal_credit=goal_credit,
                    finish_first=finish_first, look_deeper=look_deeper)
