"""The library's front door: load a task, plan a tree for it.

`plan` runs Algorithm 1 offline against the symbolic world from the problem's
initial state. Conflict resolution may move subtrees before parts of the tree that
already ran, and a tree built in one state may act differently from another, so
offline planning starts the world afresh from the initial state whenever a subtree
was moved, and once the goal is reached, runs the tree once more from the initial
state. Runs repeat (the tree keeps growing) until one reaches the goal with no
expansion at all: every tree `plan` returns reaches the goal when ticked from the
initial state, and `executed` is the action sequence of that last run.

One attempt's rounds are in `attempt`; here are the strategies and retries that choose
each attempt's options, the last resort, and plan improvement.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from btplan.acting.loop import Expansion
from btplan.acting.offline.attempt import PlanResult, Run, SearchFound, attempt
from btplan.acting.offline.whole_goal import EarlySlice, SearchTurns, WholeGoalSearch
from btplan.bt import BehaviorTree
from btplan.errors import BudgetExceededError, Interrupted, PlanningError
from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.classical import fewest_steps, no_better_plan
from btplan.records import field_values, replace

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.planner.backjump import Choice


DEFAULT_MAX_TICKS = 100_000


def load(*paths: str, problem: str | None = None) -> Task:
    """Read a domain and a problem (.bt or .pddl, one file or two) into a Task.

    A bare name that is not a file names a shipped domain, as on the command line, so
    that the examples work from any folder:

        >>> task = load("pick_place")
        >>> [str(goal) for goal in task.goal_literals]
        ['on(cube, goal)']
    """
    from btplan.lang import load as load_paths
    from btplan.shipped import resolve

    return load_paths([resolve(path) for path in paths], problem)


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
    improve: bool = True,
    say: Callable[[str], None] | None = None,
) -> PlanResult:
    """Backchain a BT for `task` by planning and acting in the symbolic world.

    Without explicit `options`, the fallback strategies run without the last-resort
    search; with `last_resort`, the default options with it come right after the
    default options without it and the goal order of the initial state (a stuck
    condition is then planned by search), and
    when every strategy fails, a plan for the whole goal is searched from the initial
    state and put behind the goal tree (with a time limit, backchaining has
    BACKCHAIN_SHARE of it). Explicit options run as they are.

    With `improve` (and the options' `improve_plan`), the executed plan is then made
    shorter within a share of the time (btplan/acting/offline/improved.py), and the tree runs
    the shorter plan; `say` hears what that step is doing.

    Raises a PlanningError (NoAchieverError, UnresolvableConflictError,
    NoProgressError, BudgetExceededError) with a reason when no tree is found, and
    Interrupted when `stop`, asked after every tick, says to stop.

    The paper's Example 1, planned: four expansions, and the plan the tree executes.

        >>> result = plan(load("pick_place"))
        >>> result.stats.expansions, result.stats.tree_size
        (4, 19)
        >>> [str(action) for action in result.executed]
        ['MoveTo(cube, tau_cube)', 'Pick(cube)', 'MoveTo(goal, tau_goal)', 'Place(cube, goal)']
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
        if last_resort:  # early: later strategies may use up the time
            at = 2 if len(strategies) > 1 and strategies[1].state_agenda else 1
            strategies.insert(at, opts)
    # The relaxed model and mutexes, built once for all; only the plan changes the state,
    # so unreachable groundings are left out unless the options keep such bindings.
    models = AchieverIndex(task, reachable_only=opts.prune_bindings)
    whole = last_resort and options is None
    soft = deadline
    if whole and timeout:  # leave the whole-goal search its share of the time
        soft = started + timeout * BACKCHAIN_SHARE
    run = Run(task, seed, max_ticks, deadline, timeout, on_expansion, started, models, stop)
    last = WholeGoalSearch(task, models, seed) if whole else None
    turns = (SearchTurns(last, started, timeout, soft)
             if last is not None and soft is not None and timeout else None)
    early = None if last is None or deadline is None else EarlySlice(last, deadline, turns)
    try:
        share = run
        if soft is not None and soft != deadline and timeout is not None:
            share = replace(run, deadline=soft, timeout=soft - started, limit=(
                f"backchaining's share ({timeout * BACKCHAIN_SHARE:g} s) of the {timeout:g} s "
                "time limit"))
        if turns is not None:
            share = replace(share, search_turn=turns.take)
        result = _strategies(share, strategies, None if early is None else (
            lambda: _early(run, opts, early)))
    except SearchFound as found:
        result = _adopt(run, opts, found.steps)
    except PlanningError as error:
        out_of_time = deadline is not None and time.perf_counter() >= deadline
        if last is None or out_of_time:
            raise
        result = _whole_goal(run, opts, error, last)
    if last is not None:
        last.release()  # the states its turns kept are not needed to improve the plan
    return _improve(run, result, say) if improve and opts.improve_plan else result




BACKCHAIN_SHARE = 0.8
"""The share of a time limit backchaining gets before the whole-goal search (the last resort)."""


def _strategies(run: Run, strategies: list[PlannerOptions],
                stalled: Callable[[], PlanResult | None] | None = None) -> PlanResult:
    """The strategies in turn; the first error, saying what the others did, when all fail.

    `stalled` is asked once the first attempt has failed; a result it returns is taken.
    """
    first_error: PlanningError | None = None
    found: PlanResult | None = None
    given_up: list[Choice] = []
    for number, strategy in enumerate(strategies):
        if number:  # the later strategies start from scratch, without retries
            strategy = replace(strategy, retries=0)
        try:
            result = _retrying(run, strategy, given_up, None if number else stalled)
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
    if given_up:
        first_error.reason += (f"; {len(given_up)} attempts started over without a choice that"
                               f" failed ({_choices(given_up)})")
    first_error.args = (first_error.reason,)
    raise first_error


def _early(run: Run, opts: PlannerOptions, early: EarlySlice) -> PlanResult | None:
    """The whole-goal search's early slice when the first attempt failed."""
    steps = early.take()
    return None if steps is None else _adopt(run, opts, steps)


def _whole_goal(run: Run, opts: PlannerOptions, backchaining: PlanningError,
                last: WholeGoalSearch) -> PlanResult:
    """The last resort when backchaining failed: search on for a plan for the whole goal
    from the initial state and put it behind the goal tree (rescue.plan_whole_goal)."""
    steps = last.resume(run.deadline)
    if last.proof is not None:
        raise type(backchaining)(f"{backchaining.reason}; and no plan exists: {last.proof}")
    if steps is None:
        raise type(backchaining)(
            f"{backchaining.reason}; then the search for the whole goal from the initial state "
            f"found no plan ({last.why(run.deadline)})")
    return _adopt(run, opts, steps)


def _improve(run: Run, result: PlanResult, say: Callable[[str], None] | None) -> PlanResult:
    """The result with a shorter plan ahead of its tree, when one is found in time."""
    started = time.perf_counter()
    relaxed, steps = run.models.relaxed, len(result.executed)
    start, goal = run.task.initial_state, run.task.goal_literals
    floor = fewest_steps(relaxed, start, goal, steps)
    if floor >= steps or (floor == 0 and no_better_plan(relaxed, start, goal, steps,
                                                         result.stats.cost)):
        # no plan is shorter (nor cheaper): the search and its imports are spared
        now = time.perf_counter()
        return replace(result, stats=replace(result.stats, removed=0, shortest=True,
                                             improve_seconds=now - started,
                                             seconds=now - run.started))
    from btplan.acting.offline.improved import budget, improve_executed

    seconds = budget(run.started, started, run.deadline)
    if seconds <= 0:
        return result  # too close to the deadline: the plan stays as found
    if say is not None:
        say(f"improving the plan of {len(result.executed)} steps (up to {seconds:.1f} s)")
    found = improve_executed(run.task, run.models, result.tree, result.executed, run.seed,
                             seconds, run.stop, floor)
    if run.stop is not None and run.stop():
        raise Interrupted(f"planning, while improving the plan of {len(result.executed)} steps")
    now = time.perf_counter()
    stats = replace(result.stats, removed=0, improve_seconds=now - started,
                    seconds=now - run.started)
    if found is None:
        return replace(result, stats=stats)
    stats.removed = len(result.executed) - len(found.executed)
    stats.eliminated = min(found.found.eliminated, stats.removed)
    stats.tree_size = len(found.tree.nodes())
    stats.actions_executed = len(found.executed)
    stats.cost = sum(a.cost for a in found.executed)
    stats.ticks += found.ticks
    return replace(result, tree=found.tree, executed=found.executed, stats=stats)


def _adopt(run: Run, opts: PlannerOptions, steps: list[GroundAction]) -> PlanResult:
    """The tree with a plan for the whole goal behind the goal tree, run from the start."""
    options = replace(opts, search_stuck=False, retries=0)
    result = attempt(run, options, plan=steps)
    result.stats.whole_goal = True
    return result


def _retrying(run: Run, opts: PlannerOptions, given_up: list[Choice],
              stalled: Callable[[], PlanResult | None] | None = None) -> PlanResult:
    """Attempts of one strategy, each after a failure without one more achiever choice.

    When an attempt stops (no conflict-free place, a dead end, a loop), the choice the
    loop blames (btplan/planner/backjump.py) is banned and the attempt starts over from
    the initial state, up to `opts.retries` times; the choices given up are
    appended to `given_up`. Raises the first attempt's error when none succeeds.
    `stalled` is asked right after the first attempt fails (the last resort's early
    slice); a result it returns is taken.
    """
    banned: list[Choice] = []
    first: PlanningError | None = None
    for number in range(opts.retries + 1):
        culprits: list[Choice] = []
        try:
            result = attempt(run, opts, frozenset(banned), culprits)
        except BudgetExceededError:
            raise
        except PlanningError as error:
            first = first or error
            rescued = stalled() if stalled is not None and number == 0 else None
            if rescued is not None:
                return rescued
            fresh = [c for c in culprits if c not in banned]
            late = run.deadline is not None and time.perf_counter() > run.started + (
                RETRY_SHARE * (run.deadline - run.started))
            if not fresh or number == opts.retries or late:
                break
            banned.append(fresh[0])
            given_up.append(fresh[0])
            continue
        result.stats.retries = len(banned)
        return result
    assert first is not None
    raise first


RETRY_SHARE = 1 / 3
"""No attempt starts over once this share of the time allowed is used: the fallback
strategies and the last resort need the rest."""


def _choices(choices: list[Choice], shown: int = 3) -> str:
    """`on(a, b) by stack(a, b), ...`: the choices given up, the first few."""
    listed = [f"{literal} by {name}({', '.join(args)})" for literal, (name, args) in choices]
    more = f", and {len(listed) - shown} more" if len(listed) > shown else ""
    return ", ".join(listed[:shown]) + more


def fallback_strategies(options: PlannerOptions) -> list[PlannerOptions]:
    """The default options, then the goal order the initial state imposes
    (`state_agenda`), the paper's breadth-first expansion order, wider fallbacks, no
    goal reordering, protected goals.

    Backchaining commits to the achievers it ranked best in the state it expanded
    in; when that leads nowhere, starting over with the breadth-first choice of the
    condition to expand (nearest-first can commit a shared resource, a free arm, too
    early), with more alternatives per condition, or with the paper's own priority
    moves only, often does. The next strategy is also
    tried when the tree's last run succeeded once with the goal still false (later work
    undid a goal within one tick); if none does better, the first tree is returned.
    Deterministic: always the same list, in the same order (so the last few are
    kept, by options, and copied: every planning call asks, and making them took a
    tenth of a small call's time).
    """
    # by the values' types too: options equal with 4 and 4.0 make different lists
    key = (options, *map(type, field_values(options)))
    found = _FALLBACKS.get(key)
    if found is None:
        if len(_FALLBACKS) >= FALLBACKS_KEPT:
            _FALLBACKS.clear()
        found = _FALLBACKS[key] = tuple(_fallbacks(options))
    return list(found)


FALLBACKS_KEPT = 8
"""Option sets whose fallback strategies are kept (a caller uses one or two)."""

_FALLBACKS: dict[tuple[object, ...], tuple[PlannerOptions, ...]] = {}


def _fallbacks(options: PlannerOptions) -> list[PlannerOptions]:
    """The list `fallback_strategies` returns, made."""
    return [
        options,
        *([replace(options, state_agenda=True)] if options.goal_agenda else []),
        *([replace(options, closest_first=False)] if options.closest_first else []),
        replace(options, max_alternatives=options.max_alternatives * 2),
        replace(options, reorder_goals=False),
        replace(options, protect_goals=True),
    ]
