"""Algorithm 1 as an acting loop: tick the tree against a world, expand it when it fails.

The tree is never rebuilt: it starts as the goal conditions and only grows, one atomic
BT per failing tick, with conflicts resolved right after each expansion. All world
access of planning lives in this package; the planner steps in btplan.planner are plain
functions. Here are the tick and ExpandTree with conflict resolution; the other parts
of the loop have modules of their own (btplan.acting.state lists them).
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable

from btplan.acting.ahead import later_false
from btplan.acting.choice import achievers_for
from btplan.acting.config import ActingConfig
from btplan.acting.diagnosis import failing_actions, loop_reason, most_expanded, no_achiever_reason
from btplan.acting.early import expand_ahead, expand_broken, expand_if_forced
from btplan.acting.finish import FinishFirst
from btplan.acting.prepare import give_up, prepare_before
from btplan.acting.progress import Circles
from btplan.acting.protect import protect
from btplan.acting.regrow import reexpand
from btplan.acting.scope import lineage, scope_moved
from btplan.acting.searched import adopt_plan, search_stuck
from btplan.acting.skills import Skills
from btplan.acting.state import Expansion, RunResult, TickReport
from btplan.bt import (
    FAILURE,
    SUCCESS,
    BehaviorTree,
    Fallback,
    LeafKey,
    Node,
)
from btplan.errors import (
    BudgetExceededError,
    NoAchieverError,
    NoProgressError,
    UnresolvableConflictError,
)
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.planner import (
    AchieverIndex,
    Judge,
    PlannerOptions,
    PlanningWorld,
    expand_tree,
    failed_conditions,
    initial_tree,
    literal_of,
    resolve_conflicts,
)
from btplan.planner.achievers import guards
from btplan.planner.agenda import goal_agenda, state_orders
from btplan.planner.expand import goal_check, guard_nodes
from btplan.planner.lookahead import closest_first
from btplan.robot.contract import World
from btplan.robot.refine import ConstraintRefiner

TYPE_CHECKING = False
if TYPE_CHECKING:  # backjump (blame), protect (an option) and rescue: when first used
    from btplan.planner.backjump import Choice
    from btplan.planner.rescue import Rescuer

__all__ = ["BlendedLoop", "Expansion", "RunResult", "TickReport"]

STUCK_EXPANSIONS = 8
"""Expansions of one condition after which it counts as stuck (for `search_stuck`)."""

ROUND_EXPANSIONS = 40
"""Expansions of one condition after which the attempt stops: it goes round, and the
next strategy (or the last-resort search) is better spent time than the budget. A task
with more objects allows one expansion per object: gripper's robot must be in a room
again for every ball, blocksworld's hand empty again for every block moved."""

BACKTRACKS = 2
"""Further batches of achievers tried when the first has no conflict-free place."""

_NO_DEPARTURES = ActingConfig.paper()
"""The departures of a loop given no configuration: none (offline planning's)."""


def _unexpand(tree: BehaviorTree, subtree: Fallback, condition: Node) -> None:
    """Undo ExpandTree: put the condition back where its atomic BT stands."""
    subtree.remove(condition)
    parent = subtree.parent
    if parent is None:
        tree.root = condition
        return
    parent.replace(subtree, condition)


class BlendedLoop:
    """Plans and acts at once (the paper's Algorithm 1) against any PlanningWorld.

    `tick()` ticks once; on FAILURE it expands the first failed condition found
    breadth first (Algorithm 3), substitutes its atomic BT (Algorithm 2) and moves it
    until no conflict is left. A condition without achievers is skipped in favour of
    the next failed one; if none has achievers, NoAchieverError names them. When the
    world comes back to a state it was in, with no expansion in between and no
    outside change, the loop is going round in circles: NoProgressError
    (btplan.acting.progress). With `look_ahead`, some conditions are expanded before a
    tick reaches them (btplan.acting.early).
    """

    def __init__(
        self,
        task: Task,
        world: World,
        options: PlannerOptions | None = None,
        like: AchieverIndex | None = None,
        banned: frozenset[Choice] = frozenset(),
        config: ActingConfig | None = None,
    ) -> None:
        """`options`: the planner's (by default `config.loop_planner`); `like`: an index of
        the same task to share models with; `banned`: (condition, action) choices never
        used (btplan.planner.backjump); `config`: which departures from Algorithm 1 act
        (btplan.acting.config; none when not given, as offline planning runs it).

        The world is reached through `Skills` (btplan.acting.skills): the loop keeps the
        logs of the robot's actions and runs each grounded action at most once at a time."""
        departures = config or _NO_DEPARTURES
        self.config = departures
        look_ahead = departures.expand_later_preconditions
        self.banned = banned
        self.culprits: list[Choice] = []
        """When planning stopped: the achiever choices to give up first (backjump.py)."""
        self.task = task
        self.look_ahead = look_ahead
        self.scope_moves = departures.skip_moved_while_held
        self.goal_credit = departures.credit_other_goals
        self.optional: set[Node] = set()
        """Conditions added before an achiever for another goal (btplan.acting.prepare)."""
        self.relaxed_plans: object | None = None
        """The relaxed plans of the index's relaxed model, kept once prepare.py asked."""
        self.ahead: list[Node] = []
        self.look_deeper = departures.expand_when_forced
        self.finish_first = departures.finish_halted_action
        self.forcing: list[Node] = []
        """Later false preconditions expanded now only if their achiever forces (ahead.py)."""
        self.options = options or (departures.loop_planner if config else PlannerOptions())
        self.grounding: dict[LeafKey, GroundAction] = {}
        self.skills = self._skills_for(world)
        self.world: PlanningWorld = self.skills
        """The world as planning and the departures see it: `Skills` over the robot."""
        self.index = AchieverIndex(task, self.options, like)
        order = None
        if self.options.goal_agenda and self.options.mutexes and len(task.goal_literals) > 1:
            relaxed = self.index.relaxed
            extra = state_orders(task.goal_literals, self.index.mutexes, relaxed,
                                 task.initial_state) if self.options.state_agenda else None
            order = goal_agenda(task.goal_literals, relaxed.producers, self.index.mutexes,
                                extra)
        self.tree = initial_tree(task, order)
        self.finishing = FinishFirst(self.skills, self.grounding) if self.finish_first else None
        self.expansions: list[Expansion] = []
        self.ticks = 0
        self.expanded: set[Node] = set()
        self.dead: set[Node] = set()
        self._guards_seen: set[Node] = set()
        self._judged: tuple[int, frozenset[Atom] | None, Judge] | None = None  # see judge()
        self.circular: set[GroundLiteral] = set()
        self._circles = Circles()
        self._last_state: frozenset[Atom] | None = None
        self._stalls = 0
        self.premature_successes = 0
        self.searches = 0
        """Stuck conditions planned by the last-resort search (`search_stuck`)."""
        self.deadline: float | None = None
        """A time.perf_counter() value the last-resort search must not run past."""
        self.rescuer: Rescuer | None = None
        self._tally: Counter[GroundLiteral] = Counter()
        self._round_limit = max(ROUND_EXPANSIONS, len(task.object_types))
        check = goal_check(self.tree)
        if check is not None:  # the final re-check of the goals is never expanded
            self.expanded.update(check.children)
            self.dead.update(check.children)

    def _skills_for(self, world: World) -> Skills:
        refiner = None if callable(getattr(world, "refine", None)) else \
            ConstraintRefiner(self.task, lambda: self.skills.facts())
        return Skills(world, self.grounding, self.config.stop_on_skill_error, refiner)

    def use_world(self, world: World) -> None:
        """Keep the tree and continue against another world (a fresh run from the start)."""
        self.tree.halt(self.skills)
        self.skills.halt_all(self.config.halt_wait)
        self.skills = self._skills_for(world)
        self.world = self.skills
        if self.finishing is not None:
            self.finishing = FinishFirst(self.skills, self.grounding)
        self._circles.forget()
        self._last_state = None
        self._stalls = 0

    # --- one tick ----------------------------------------------------------------------

    def tick(self) -> TickReport:
        before = self.world.facts()
        if before != self._last_state:
            self._circles.forget()  # an outside change: a repeated state is no longer a loop
        self.ticks += 1
        report = TickReport(self.ticks, FAILURE)
        if self.look_ahead and self._last_state is not None and before != self._last_state:
            expand_broken(self, report, self._last_state)
        while True:
            self.skills.begin_tick()
            status = report.status = self.tree.tick(self.finishing or self.skills)
            if status is not FAILURE:
                self._stalls = 0
                break
            started = time.process_time()
            try:
                expansion = self._expand()
                if expansion is not None:
                    report.expansions.append(expansion)
                    expand_ahead(self, report)
                    expand_if_forced(self, report)
            finally:
                report.planning_seconds += time.process_time() - started
            if expansion is not None:
                self._stalls = 0
                if len(report.expansions) < self.options.expansions_per_tick:
                    continue  # the world has not moved: tick the grown tree at once
            elif self.world.facts() != before:
                self._stalls = 0  # work was done; the goal check sent it round again
            else:
                self._stall()
            break
        if self.finishing is not None:
            self.finishing.end_tick()
        after = self.world.facts()
        if self._circles.repeated(self.skills, before, after, len(self.expansions)):
            executed = self.skills.executed
            if executed:  # the same state under the same tree: drop what ran in the loop
                from btplan.planner.backjump import running_choices

                self.culprits = running_choices(self.tree.root, executed[-1].key)
            raise NoProgressError(loop_reason(len(self.expansions), self.skills))
        self._last_state = after
        return report

    def _expand(self) -> Expansion | None:
        state = self.world.facts()
        missing: list[GroundLiteral] = []
        stuck: list[Node] = []
        failed = failed_conditions(self.tree, self.expanded)
        if self.options.closest_first and len(failed) > 1:
            failed = closest_first(failed, self.index.relaxed, state)
        for node in failed:
            literal = literal_of(node)
            assert literal is not None
            if literal.holds(state):
                # Measured again since the tick found it false (a simulator re-plans a
                # path once the move that drove it halts): nothing to achieve, and its
                # achievers, looked up in these facts, would be none. The next tick
                # passes it.
                continue
            if self._tally[literal] >= STUCK_EXPANSIONS:
                searched = search_stuck(self, node)  # expanded again and again: going round
                if searched is not None:
                    return searched
                if self._tally[literal] >= self._round_limit and self.options.refine_more:
                    from btplan.planner.backjump import enclosing_choices

                    self.culprits = enclosing_choices(node)
                    raise NoProgressError(
                        f"{literal} was expanded {self._tally[literal]} times: the tree goes "
                        f"round (expanded most often: {self.most_expanded()})")
            achievers, spare = achievers_for(self, node, literal, state)
            if node in self.optional and not achievers and give_up(node):
                return self._expand()
            self.expanded.add(node)
            if not achievers:
                self.dead.add(node)
                missing.append(literal)
                stuck.append(node)
                continue
            if self.look_ahead:  # before ExpandTree moves the node under a Fallback
                self.ahead = later_false(node, state, self.expanded)
            elif self.look_deeper:
                self.forcing = later_false(node, state, self.expanded)
            try:
                return self.apply(node, literal, achievers, spare)
            except UnresolvableConflictError:
                if node not in self.optional or not give_up(node):
                    raise
                return self._expand()  # a prepared condition, given up (prepare.py)
        more = reexpand(self, state) if self.options.refine_more else None
        if more is not None:
            return more
        for node in stuck:
            searched = search_stuck(self, node)
            if searched is not None:
                return searched
        if missing:
            from btplan.planner.backjump import enclosing_choices

            self.culprits = list(dict.fromkeys(c for n in stuck for c in enclosing_choices(n)))
            raise NoAchieverError(no_achiever_reason(missing, self.index, self.circular,
                                                     len(self.expansions), self.skills))
        return None

    def most_expanded(self, count: int = 3) -> str:
        """The conditions expanded most often, `on(a, b) (7)`: where the search went round."""
        return most_expanded(self.expansions, count)

    def record(
        self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int, moves: int
    ) -> Expansion:
        expansion = Expansion(self.ticks, str(literal), [str(a) for a in achievers], conflicts,
                              moves)
        self._tally[literal] += 1
        self.expansions.append(expansion)
        return expansion

    def apply(
        self, node: Node, literal: GroundLiteral, achievers: list[GroundAction],
        spare: list[GroundAction] | None = None,
    ) -> Expansion:
        """ExpandTree (Algorithm 2), then IncreasePriority while in conflict (lines 11-12).

        With `backtrack`, when no place is free of conflicts, the subtree is taken out
        again and the next-ranked achievers are tried instead (up to BACKTRACKS more
        batches): another way of achieving the condition may fit where this one cannot.
        """
        if len(self.expansions) >= self.options.max_expansions:
            raise BudgetExceededError(
                f"the expansion budget ({self.options.max_expansions}) ran out "
                f"while {literal} still fails; expanded most often: {self.most_expanded()}"
            )
        width = self.options.max_alternatives
        batches = [achievers]
        if self.options.backtrack and spare:
            batches += [spare[i:i + width] for i in range(0, len(spare), width)][:BACKTRACKS]
        first: UnresolvableConflictError | None = None
        state = self.world.facts()
        for batch in batches:
            for action in batch:
                self.grounding[action.key] = action
            guarded = self._guards(batch, literal, state)
            subtree = expand_tree(self.tree, node, batch, self.task, guarded)
            self.never_expand(guard_nodes(subtree, guarded))
            if self.goal_credit:  # set up what the first achiever enables
                self.ahead += prepare_before(self, subtree, batch[0], literal, state)
            if self.options.protect_goals:
                protect(self, subtree)
            before = lineage(subtree) if self.scope_moves else []
            try:
                resolution = resolve_conflicts(
                    self.tree, subtree, self.judge(), self.options.reorder_goals,
                    self.options.refine_more,
                )
            except UnresolvableConflictError as error:
                if first is None:
                    from btplan.planner.backjump import conflict_choices

                    first = error
                    self.culprits = conflict_choices(subtree, self.judge())
                _unexpand(self.tree, subtree, node)
                continue
            if resolution.moves and before:
                self.never_expand(scope_moved(before, self.task))
            return self.record(literal, batch, len(resolution.conflicts), resolution.moves)
        assert first is not None
        if node in self.optional:
            raise first  # an extra: given up, not searched for (prepare.py)
        searched = search_stuck(self, node)
        if searched is not None:
            return searched
        raise first

    @staticmethod
    def _guards(
        actions: list[GroundAction], literal: GroundLiteral, state: frozenset[Atom]
    ) -> dict[LeafKey, tuple[GroundLiteral, ...]]:
        """Guards for the achievers of a wildcard condition (achievers.guards)."""
        return {a.key: g for a in actions if (g := guards(a, literal, state))}

    def never_expand(self, nodes: list[Node]) -> None:
        """Guards say what an alternative is for; they are checked, never achieved."""
        self.expanded.update(nodes)
        self.dead.update(nodes)
        self._guards_seen.update(nodes)

    def adopt_plan(self, steps: list[GroundAction]) -> None:
        """Put a plan for the whole goal behind the goal tree (`plan_whole_goal`)."""
        adopt_plan(self, steps)

    def judge(self) -> Judge:
        """What conflict checks know now; kept until a guard is added (guards are only
        added: their number tells) or the state changes. Copying the guards grew with the tree."""
        state = self.world.facts() if self.options.reorder_goals else None
        last = self._judged
        if last is not None and last[0] == len(self._guards_seen) and last[1] == state:
            return last[2]
        mutexes = self.index.mutexes if self.options.mutexes else None
        if state is None:  # the paper: no circularity check on places
            judge = Judge(self.grounding, mutexes, frozenset(self._guards_seen))
        else:
            judge = Judge(self.grounding, mutexes, frozenset(self._guards_seen),
                          self.index.relaxed, state)
        self._judged = (len(self._guards_seen), state, judge)
        return judge

    def _stall(self) -> None:
        """The tree failed with nothing to expand (an action failed): retry, a few times."""
        self._stalls += 1
        if self._stalls > self.options.stall_limit:
            failing = ", ".join(failing_actions(self.tree.root)) or "none"
            raise NoProgressError(
                f"the tree failed {self._stalls} ticks in a row with no condition left "
                f"to expand; failing actions: {failing}"
            )

    def goal_holds(self) -> bool:
        state = self.world.facts()
        return all(g.holds(state) for g in self.task.goal_literals)

    # --- many ticks --------------------------------------------------------------------

    def run(
        self,
        max_ticks: int,
        before_tick: Callable[[int], None] | None = None,
        on_tick: Callable[[TickReport], None] | None = None,
    ) -> RunResult:
        """Tick until the tree succeeds with the goal true, or `max_ticks` ticks were spent.

        The goal is checked in the world after the tick: when actions finish within
        the tick they start in, later work may undo a goal checked earlier in the
        same tick, and the next tick must then put it right.
        """
        start = len(self.expansions)
        for i in range(max_ticks):
            if before_tick is not None:
                before_tick(self.ticks + 1)
            report = self.tick()
            if on_tick is not None:
                on_tick(report)
            if report.status is SUCCESS:
                if self.goal_holds():
                    return RunResult(True, i + 1, self.expansions[start:], self.tree,
                                     "goal reached")
                self.premature_successes += 1
        return RunResult(
            False, max_ticks, self.expansions[start:], self.tree,
            f"the goal was not reached within {max_ticks} ticks",
        )

