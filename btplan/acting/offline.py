"""The library's front door: load a task, plan a tree for it.

`plan` runs Algorithm 1 offline against the symbolic world from the problem's
initial state. Conflict resolution may move subtrees before parts of the tree that
already ran, and a tree built in one state may act differently from another, so
offline planning starts the world afresh from the initial state whenever a subtree
was moved, and once the goal is reached, runs the tree once more from the initial
state. Runs repeat (the tree keeps growing) until one reaches the goal with no
expansion at all: every tree `plan` returns reaches the goal when ticked from the
initial state, and `executed` is the action sequence of that last run.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from btplan.acting.loop import BlendedLoop, Expansion, TickReport
from btplan.bt import BehaviorTree, LeafKey
from btplan.errors import BudgetExceededError, Interrupted, PlanningError
from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.worlds.symbolic import SymbolicWorld

if TYPE_CHECKING:
    from btplan.acting.online import RunOutcome as RunOutcome  # noqa: PLC0414
    from btplan.acting.online import run as run  # noqa: PLC0414


def __getattr__(name: str) -> Any:
    """Acting with disturbances (`btplan.run`) lives in btplan.acting.online and is
    re-exported here, imported on first use: planning does not need it."""
    if name in ("run", "RunOutcome"):
        from btplan.acting import online

        return getattr(online, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


DEFAULT_MAX_TICKS = 100_000


def load(*paths: str, problem: str | None = None) -> Task:
    """Read a domain and a problem (.bt or .pddl, one file or two) into a Task."""
    from btplan.lang import load as load_paths

    return load_paths(list(paths), problem)


@dataclass
class PlanStats:
    expansions: int
    conflicts_resolved: int
    moves: int
    tree_size: int
    actions_executed: int
    ticks: int
    rounds: int
    seconds: float
    premature_successes: int = 0
    searches: int = 0
    """Stuck conditions planned by the last-resort search and inserted as subtrees."""
    cost: float = 0.0
    """The executed plan's cost: the sum of its actions' costs (its length in unit cost)."""


@dataclass
class PlanResult:
    """The final tree, the actions its last run executed, and what planning cost."""

    tree: BehaviorTree
    executed: list[GroundAction]
    stats: PlanStats
    expansions: list[Expansion] = field(default_factory=list)


def plan(
    task: Task,
    *,
    seed: int = 0,
    max_expansions: int | None = None,
    max_ticks: int = DEFAULT_MAX_TICKS,
    timeout: float | None = None,
    options: PlannerOptions | None = None,
    on_expansion: Callable[[BehaviorTree, Expansion], None] | None = None,
    stop: Callable[[], bool] | None = None,
    last_resort: bool = True,
) -> PlanResult:
    """Backchain a BT for `task` by planning and acting in the symbolic world.

    Without explicit `options`, the fallback strategies run without the last-resort
    search; with `last_resort`, the default options with it come second, right after
    the default options without it (a stuck condition is then planned by search).
    Explicit options run as they are.

    Raises a PlanningError (NoAchieverError, UnresolvableConflictError,
    NoProgressError, BudgetExceededError) with a reason when no tree is found, and
    Interrupted when `stop`, asked after every tick, says to stop.
    """
    opts = options or PlannerOptions()
    if max_expansions is not None:
        opts = replace(opts, max_expansions=max_expansions)
    started = time.perf_counter()
    deadline = None if timeout is None else started + timeout
    if options is not None:
        strategies = [opts]
    else:
        strategies = fallback_strategies(replace(opts, search_stuck=False))
        if last_resort:  # right after the default: later strategies may use up the time
            strategies.insert(1, opts)
    first_error: PlanningError | None = None
    found: PlanResult | None = None
    models = AchieverIndex(task)  # the relaxed model and mutexes, built once for all
    for strategy in strategies:
        try:
            result = _attempt(task, seed, strategy, max_ticks, deadline, timeout, on_expansion,
                              started, models, stop)
        except BudgetExceededError:
            if found is not None:
                return found
            raise
        except PlanningError as error:
            first_error = first_error or error
            continue
        if result.stats.premature_successes == 0:
            return result
        found = found or result
    if found is not None:
        return found
    assert first_error is not None
    if len(strategies) > 1:
        first_error.reason += f" (and {len(strategies) - 1} fallback strategies failed too)"
        first_error.args = (first_error.reason,)
    raise first_error


def fallback_strategies(options: PlannerOptions) -> list[PlannerOptions]:
    """The default options, then the paper's breadth-first expansion order, wider
    fallbacks, no goal reordering, protected goals.

    Backchaining commits to the achievers it ranked best in the state it expanded
    in; when that leads nowhere, starting over with the breadth-first choice of the
    condition to expand (nearest-first can commit a shared resource, a free arm, too
    early), with more alternatives per condition, or with the paper's own priority
    moves only, often does. The next strategy is also
    tried when the tree's last run succeeded once with the goal still false (later work
    undid a goal within one tick); if none does better, the first tree is returned.
    Deterministic: always the same list, in the same order.
    """
    return [
        options,
        *([replace(options, closest_first=False)] if options.closest_first else []),
        replace(options, max_alternatives=options.max_alternatives * 2),
        replace(options, reorder_goals=False),
        replace(options, protect_goals=True),
    ]


def _attempt(
    task: Task,
    seed: int,
    opts: PlannerOptions,
    max_ticks: int,
    deadline: float | None,
    timeout: float | None,
    on_expansion: Callable[[BehaviorTree, Expansion], None] | None,
    started: float,
    models: AchieverIndex,
    stop: Callable[[], bool] | None = None,
) -> PlanResult:
    """Rounds of Algorithm 1 from the initial state until one needs no expansion."""
    groundings: dict[LeafKey, GroundAction] = {}
    world = SymbolicWorld(task, seed=seed, groundings=groundings)
    loop = BlendedLoop(task, world, opts, like=models)
    loop.deadline = deadline
    ticks_left = max_ticks

    def watch(report: TickReport) -> None:
        if stop is not None and stop():
            loop.tree.halt(loop.world)
            raise Interrupted(f"{len(loop.expansions)} expansions and {loop.ticks} ticks "
                              f"(tree of {len(loop.tree.nodes())} nodes)")
        if deadline is not None and time.perf_counter() > deadline:
            raise BudgetExceededError(
                f"time limit of {timeout:g} s reached after {len(loop.expansions)} expansions "
                f"(tree of {len(loop.tree.nodes())} nodes); expanded most often: "
                f"{loop.most_expanded() or 'nothing'}")
        if on_expansion is not None:
            for expansion in report.expansions:
                on_expansion(loop.tree, expansion)
        if any(e.moves for e in report.expansions):
            raise _Restart(report.tick)

    # Every run but the last expands at least once, so the expansion budget bounds them.
    max_rounds = opts.max_expansions + 1
    for rounds in range(1, max_rounds + 1):
        if rounds > 1:
            world = SymbolicWorld(task, seed=seed, groundings=groundings)
            loop.use_world(world)
        ticks_before = loop.ticks
        premature_before = loop.premature_successes
        try:
            result = loop.run(ticks_left, on_tick=watch)
        except _Restart:
            ticks_left -= loop.ticks - ticks_before
            continue
        ticks_left -= result.ticks
        if not result.reached:
            raise BudgetExceededError(result.reason)
        if not result.expansions:
            return PlanResult(
                tree=loop.tree,
                executed=list(world.executed),
                stats=_stats(loop, world, rounds, time.perf_counter() - started,
                             loop.premature_successes - premature_before),
                expansions=list(loop.expansions),
            )
    raise PlanningError(
        f"after {max_rounds} runs from the initial state the tree still needed "
        "expansions; the order it found depends on the state it was built in"
    )


class _Restart(Exception):
    """A subtree moved: start the world afresh from the initial state."""


def _stats(
    loop: BlendedLoop, world: SymbolicWorld, rounds: int, seconds: float, premature: int
) -> PlanStats:
    return PlanStats(
        expansions=len(loop.expansions),
        conflicts_resolved=sum(e.conflicts_resolved for e in loop.expansions),
        moves=sum(e.moves for e in loop.expansions),
        tree_size=len(loop.tree.nodes()),
        actions_executed=len(world.executed),
        ticks=loop.ticks,
        rounds=rounds,
        seconds=seconds,
        premature_successes=premature,
        searches=loop.searches,
        cost=sum(a.cost for a in world.executed),
    )
