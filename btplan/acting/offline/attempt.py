"""One attempt of offline planning: rounds of Algorithm 1 from the initial state.

An attempt starts the symbolic world afresh whenever a subtree was moved and runs
until a round needs no expansion; what it returns is the tree, the actions of that
last round, and what planning cost. The strategies and retries that choose the
options of each attempt are in `offline`.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from btplan.acting.loop import BlendedLoop, Expansion, TickReport
from btplan.acting.state import LoopMemory
from btplan.bt import BehaviorTree, LeafKey
from btplan.errors import BudgetExceededError, Interrupted, PlanningError
from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.records import field, record
from btplan.worlds.symbolic import SymbolicWorld

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.planner.backjump import Choice


@record
class PlanStats:
    """What planning cost and made: expansions, conflicts and moves, the tree, the plan,
    the rounds and the time."""

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
    retries: int = 0
    """Attempts started over, each without an achiever choice that failed (backjump.py)."""
    whole_goal: bool = False
    """Whether the tree is the last resort's: a searched plan for the whole goal."""
    removed: int | None = None
    """Steps plan improvement took out of the executed plan (None: not tried)."""
    eliminated: int = 0
    """Of those, the ones action elimination took out (the rest: plan-neighbourhood search)."""
    improve_seconds: float = 0.0
    """Time plan improvement took."""
    shortest: bool = False
    """Whether a lower bound showed that no plan has fewer steps (btplan/classical/bound.py),
    so plan improvement had nothing to look for."""


@record
class PlanResult:
    """The final tree, the actions its last run executed, and what planning cost."""

    tree: BehaviorTree
    executed: list[GroundAction]
    stats: PlanStats
    expansions: list[Expansion] = field(default_factory=list)
    memory: LoopMemory | None = None
    """What the loop that grew the tree knew of it (for acting on it online)."""


@record(frozen=True)
class Run:
    """What every attempt of one `plan` call shares: the task, its limits, its callbacks."""

    task: Task
    seed: int
    max_ticks: int
    deadline: float | None
    timeout: float | None
    on_expansion: Callable[[BehaviorTree, Expansion], None] | None
    started: float
    models: AchieverIndex
    stop: Callable[[], bool] | None
    limit: str = ""
    """How a failure names the time limit that ran out, when it is not `timeout` itself."""
    search_turn: Callable[[Callable[[], int]], list[GroundAction] | None] | None = None
    """Asked after every tick with a count of the goals the attempt holds now: gives the
    whole-goal search its turn when one is due, and returns the plan it found then
    (whole_goal.SearchTurns)."""


class SearchFound(Exception):
    """The whole-goal search found a plan in its turn: the attempt stops for it."""

    def __init__(self, steps: list[GroundAction]) -> None:
        super().__init__(f"a plan of {len(steps)} steps")
        self.steps = steps


def attempt(
    run: Run,
    opts: PlannerOptions,
    banned: frozenset[Choice] = frozenset(),
    culprits: list[Choice] | None = None,
    plan: list[GroundAction] | None = None,
) -> PlanResult:
    """Rounds of Algorithm 1 from the initial state until one needs no expansion.

    `banned` choices are never used; when planning stops, `culprits` receives the
    choices the loop blames. `plan`, a plan for the whole goal, goes behind the goal
    tree before the first tick.
    """
    groundings = run.models.groundings  # the same `instantiate`, kept with the domain
    world = SymbolicWorld(run.task, seed=run.seed, groundings=groundings)
    loop = BlendedLoop(run.task, world, opts, like=run.models, banned=banned,
                       deadline=run.deadline)
    if plan is not None:
        loop.adopt_plan(plan)
    try:
        return _rounds(run, opts, loop, groundings)
    finally:
        if culprits is not None:
            culprits.extend(loop.culprits)


def _rounds(
    run: Run, opts: PlannerOptions, loop: BlendedLoop, groundings: dict[LeafKey, GroundAction]
) -> PlanResult:
    """The runs of one attempt, each from the initial state."""
    task, seed, deadline, stop, on_expansion = (run.task, run.seed, run.deadline, run.stop,
                                                run.on_expansion)
    world = loop.skills.world
    assert isinstance(world, SymbolicWorld)
    ticks_left = run.max_ticks
    goals = task.goal_literals

    def headway() -> int:
        """The goals the attempt's world holds now (the search's turns judge by it)."""
        state = loop.world.facts()
        return sum(1 for goal in goals if goal.holds(state))

    def watch(report: TickReport) -> None:
        if stop is not None and stop():
            loop.tree.halt(loop.world)
            raise Interrupted(f"{len(loop.expansions)} expansions and {loop.ticks} ticks "
                              f"(tree of {len(loop.tree.nodes())} nodes)")
        if deadline is not None and time.perf_counter() > deadline:
            raise BudgetExceededError(
                f"{run.limit or f'time limit of {run.timeout:g} s'} reached after {len(loop.expansions)} expansions "
                f"(tree of {len(loop.tree.nodes())} nodes); expanded most often: "
                f"{loop.most_expanded() or 'nothing'}")
        if on_expansion is not None:
            for expansion in report.expansions:
                on_expansion(loop.tree, expansion)
        if run.search_turn is not None:
            steps = run.search_turn(headway)
            if steps is not None:
                raise SearchFound(steps)
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
        if not result.expansions or _replays_itself(loop, world):
            return PlanResult(
                tree=loop.tree,
                executed=list(world.executed),
                stats=_stats(loop, world, rounds, time.perf_counter() - run.started,
                             loop.premature_successes - premature_before),
                expansions=list(loop.expansions),
                memory=loop.memory(),
            )
    raise PlanningError(
        f"after {max_rounds} runs from the initial state the tree still needed "
        "expansions; the order it found depends on the state it was built in"
    )


def _replays_itself(loop: BlendedLoop, world: SymbolicWorld) -> bool:
    """Whether the run just ended is already a run of its final tree from the initial
    state, so that another round would only repeat it: every expansion was made before
    any action started, and nothing was left to chance. The tree then met the initial
    state as it stands, ran from there, and the world has no other outcome to give.
    (Most small calls expand only in their first tick: this spares them half their
    ticking.)"""
    return loop.started_before_expansion == 0 and not world.drew


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
