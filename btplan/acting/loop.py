"""Algorithm 1 as an acting loop: tick the tree against a world, expand it when it fails.

The tree is never rebuilt: it starts as the goal conditions and only grows, an atomic
BT at a time, with conflicts resolved right after each expansion. The loop calls the
paper's steps by name: `get_condition_to_expand` (Algorithm 3), `expand_tree`
(Algorithm 2) and `increase_priority` (Algorithm 1, lines 11-12). Everything beyond
the published algorithm is a departure behind the hooks of btplan.acting.hooks
(btplan.acting.departures); with none, this is Algorithm 1. The robot is reached
through `Skills` (btplan.acting.skills), which keeps the logs of its actions.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable, Iterable

from btplan.acting.choice import achievers_for
from btplan.acting.config import ActingConfig
from btplan.acting.departures import departures_for
from btplan.acting.departures.ahead import attached
from btplan.acting.departures.search import adopt_plan
from btplan.acting.diagnosis import failing_actions, loop_reason, most_expanded, no_achiever_reason
from btplan.acting.early import EarlyExpansions
from btplan.acting.hooks import Departure, Hooks
from btplan.acting.progress import Circles
from btplan.acting.skills import Skills
from btplan.acting.state import Expansion, LoopMemory, RunResult, TickReport
from btplan.bt import FAILURE, SUCCESS, BehaviorTree, Fallback, LeafKey, Node
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
from btplan.planner.priority import Resolution
from btplan.robot.contract import World, capabilities_of
from btplan.robot.refine import ConstraintRefiner

TYPE_CHECKING = False
if TYPE_CHECKING:  # backjump (blame): when first used
    from btplan.planner.backjump import Choice

__all__ = ["BlendedLoop", "Expansion", "RunResult", "TickReport"]

STUCK_EXPANSIONS = 8
"""Expansions of one condition after which it counts as stuck (`Hooks.when_stuck`)."""

ROUND_EXPANSIONS = 40
"""Expansions of one condition after which the attempt stops: it goes round, and the
next strategy (or the last-resort search) is better spent time than the budget. A task
with more objects allows one expansion per object: gripper's robot must be in a room
again for every ball, blocksworld's hand empty again for every block moved."""

BACKTRACKS = 2
"""Further batches of achievers tried when the first has no conflict-free place."""

_NO_DEPARTURES = ActingConfig.paper()
"""The departures of a loop given no configuration: none (offline planning's)."""


class BlendedLoop:
    """Plans and acts at once (the paper's Algorithm 1) against any world.

    `tick()` ticks once; on FAILURE it expands the first failed condition found
    breadth first (Algorithm 3), substitutes its atomic BT (Algorithm 2) and moves it
    until no conflict is left. A condition without achievers is skipped in favour of
    the next failed one; if none has achievers, NoAchieverError names them. When the
    world comes back to a state it was in, with no expansion in between and no
    outside change, the loop is going round in circles: NoProgressError
    (btplan.acting.progress).
    """

    def __init__(
        self,
        task: Task,
        world: World,
        options: PlannerOptions | None = None,
        like: AchieverIndex | None = None,
        banned: frozenset[Choice] = frozenset(),
        config: ActingConfig | None = None,
        deadline: float | None = None,
        departures: list[Departure] | None = None,
    ) -> None:
        """`options`: the planner's (by default `config.loop_planner`); `like`: an index of
        the same task to share models with; `banned`: (condition, action) choices never
        used (btplan.planner.backjump); `config`: which departures act (none when not
        given, as offline planning runs it); `deadline`: a time.perf_counter() value the
        last-resort search must not run past; `departures`: instead of those `config`
        and `options` switch on (btplan.acting.departures.departures_for)."""
        self.config = config or _NO_DEPARTURES
        self.task = task
        self.banned = banned
        self.deadline = deadline
        self.options = options or (self.config.loop_planner if config else PlannerOptions())
        self.grounding: dict[LeafKey, GroundAction] = {}
        self.skills = self._skills_for(world)
        self.world: PlanningWorld = self.skills
        """The world as planning and the departures see it: `Skills` over the robot."""
        self.index = AchieverIndex(task, self.options, like)
        self.tree = initial_tree(task, self._goal_order())
        self.expansions: list[Expansion] = []
        self.started_before_expansion = 0
        """Skills started in the world of the latest expansion before it was made: none, and
        the tree it left behaves from that world's start as it did (offline planning's
        rounds, btplan.acting.offline.attempt)."""
        self.ticks = 0
        self.expanded: set[Node] = set()
        self.dead: set[Node] = set()
        self.circular: set[GroundLiteral] = set()
        """Conditions whose achievers all needed what an enclosing Fallback pursues."""
        self.culprits: list[Choice] = []
        """When planning stopped: the achiever choices to give up first (backjump.py)."""
        self.premature_successes = 0
        self.searches = 0
        """Plans found by search adopted into the tree (`adopt`)."""
        self.early = EarlyExpansions(self)
        self.hooks = Hooks(departures if departures is not None
                           else departures_for(self.config, self.options))
        self._guards_seen: set[Node] = set()
        self._judged: tuple[int, frozenset[Atom] | None, Judge] | None = None  # see judge()
        self._circles = Circles()
        self._last_state: frozenset[Atom] | None = None
        self._stalls = 0
        self._tally: Counter[GroundLiteral] = Counter()
        self._round_limit = max(ROUND_EXPANSIONS, len(task.object_types))
        check = goal_check(self.tree)
        if check is not None:  # the final re-check of the goals is never expanded
            self.expanded.update(check.children)
            self.dead.update(check.children)
        self.hooks.attach(self)

    def _goal_order(self) -> list[GroundLiteral] | None:
        """The goals in the order their reasonable orders ask (planner.agenda), if asked."""
        options, task = self.options, self.task
        if not (options.goal_agenda and options.mutexes and len(task.goal_literals) > 1):
            return None
        relaxed = self.index.relaxed
        extra = state_orders(task.goal_literals, self.index.mutexes, relaxed,
                             task.initial_state) if options.state_agenda else None
        return goal_agenda(task.goal_literals, relaxed.producers, self.index.mutexes, extra)

    def _skills_for(self, world: World) -> Skills:
        refiner = None if capabilities_of(world).refines else \
            ConstraintRefiner(self.task, lambda: self.skills.facts())
        return Skills(world, self.grounding, self.config.stop_on_skill_error, refiner,
                      self.config.wait_for_alternatives)

    def use_world(self, world: World) -> None:
        """Keep the tree and continue against another world (a fresh run from the start)."""
        self.tree.halt(self.skills)
        self.skills.halt_all(self.config.halt_wait)
        self.skills = self._skills_for(world)
        self.world = self.skills
        self.hooks.new_world(self.skills)
        self._circles.forget()
        self._last_state = None
        self._stalls = 0

    # --- Algorithm 1: one tick ---------------------------------------------------------

    def tick(self) -> TickReport:
        """Tick the tree; while it fails, expand it (up to the tick's expansion budget)."""
        before = self.world.facts()
        if before != self._last_state:
            self._circles.forget()  # an outside change: a repeated state is no longer a loop
        self.ticks += 1
        report = TickReport(self.ticks, FAILURE)
        if self._last_state is not None and before != self._last_state:
            self.hooks.before_tick(report, self._last_state)
        while True:
            self.skills.begin_tick()
            status = report.status = self.tree.tick(self.hooks.world_for_tick(self.skills))
            if status is not FAILURE:
                self._stalls = 0
                break
            started = time.process_time()
            try:
                expansion = self.expand()
                if expansion is not None:
                    report.add(expansion)
                    self.early.run(report)
                    self.hooks.after_expansion(report)
            finally:
                report.add_planning(time.process_time() - started)
            if expansion is not None:
                self._stalls = 0
                if len(report.expansions) < self.options.expansions_per_tick:
                    continue  # the world has not moved: tick the grown tree at once
            elif self.world.facts() != before:
                self._stalls = 0  # work was done; the goal check sent it round again
            else:
                self._stall()
            break
        self.hooks.end_tick()
        self._check_progress(before)
        return report

    def _check_progress(self, before: frozenset[Atom]) -> None:
        after = self.world.facts()
        if self._circles.repeated(self.skills, before, after, len(self.expansions)):
            executed = self.skills.executed
            if executed:  # the same state under the same tree: drop what ran in the loop
                from btplan.planner.backjump import running_choices

                self.culprits = running_choices(self.tree.root, executed[-1].key)
            raise NoProgressError(loop_reason(len(self.expansions), self.skills))
        self._last_state = after

    # --- Algorithm 1, lines 9-12: expanding the tree -------------------------------------

    def get_condition_to_expand(self, state: frozenset[Atom]) -> list[Node]:
        """Algorithm 3, in order of preference: the failed conditions not expanded yet,
        breadth first (nearest to the state first with `closest_first`). The loop takes
        the first that has achievers."""
        failed = failed_conditions(self.tree, self.expanded)
        if self.options.closest_first and len(failed) > 1:
            failed = closest_first(failed, self.index.relaxed, state)
        return failed

    def expand(self) -> Expansion | None:
        """Expand the condition Algorithm 3 gives; None when there is nothing to expand."""
        state = self.world.facts()
        missing: list[GroundLiteral] = []
        stuck: list[Node] = []
        for node in self.get_condition_to_expand(state):
            literal = literal_of(node)
            assert literal is not None
            if literal.holds(state):
                # Measured again since the tick found it false (a simulator re-plans a
                # path once the move that drove it halts): nothing to achieve, and its
                # achievers, looked up in these facts, would be none. The next tick
                # passes it.
                continue
            if self._tally[literal] >= STUCK_EXPANSIONS:
                searched = self.hooks.when_stuck(node)  # expanded again and again
                if searched is not None:
                    return searched
                self._stop_going_round(node, literal)
            achievers, spare = self.achievers(node, literal, state)
            if not achievers and self.hooks.gives_up(node):
                return self.expand()
            self.expanded.add(node)
            if not achievers:
                self.dead.add(node)
                missing.append(literal)
                stuck.append(node)
                continue
            self.hooks.before_expansion(node, state)
            try:
                return self.apply(node, literal, achievers, spare)
            except UnresolvableConflictError:
                if not self.hooks.gives_up(node):
                    raise
                return self.expand()  # an optional condition, given up
        more = self.hooks.expand_again(state)
        if more is not None:
            return more
        for node in stuck:
            searched = self.hooks.when_stuck(node)
            if searched is not None:
                return searched
        if missing:
            from btplan.planner.backjump import enclosing_choices

            self.culprits = list(dict.fromkeys(c for n in stuck for c in enclosing_choices(n)))
            raise NoAchieverError(no_achiever_reason(missing, self.index, self.circular,
                                                     len(self.expansions), self.skills))
        return None

    def _stop_going_round(self, node: Node, literal: GroundLiteral) -> None:
        if self._tally[literal] >= self._round_limit and self.options.refine_more:
            from btplan.planner.backjump import enclosing_choices

            self.culprits = enclosing_choices(node)
            raise NoProgressError(
                f"{literal} was expanded {self._tally[literal]} times: the tree goes "
                f"round (expanded most often: {self.most_expanded()})")

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
            subtree = self.expand_tree(node, literal, batch, state)
            try:
                resolution = self.increase_priority(subtree)
            except UnresolvableConflictError as error:
                if first is None:
                    from btplan.planner.backjump import conflict_choices

                    first = error
                    self.culprits = conflict_choices(subtree, self.judge())
                self._unexpand(subtree, node)
                continue
            self.hooks.placed(subtree, resolution.moves)
            return self.record(literal, batch, len(resolution.conflicts), resolution.moves)
        assert first is not None
        if self.hooks.optional(node):
            raise first  # an optional condition: given up, not searched for
        searched = self.hooks.when_stuck(node)
        if searched is not None:
            return searched
        raise first

    def expand_tree(self, node: Node, literal: GroundLiteral, batch: list[GroundAction],
                    state: frozenset[Atom]) -> Fallback:
        """Algorithm 2: replace `node` by its atomic BT with `batch` as the achievers."""
        self.ground(batch)
        guarded = {a.key: g for a in batch if (g := guards(a, literal, state))}
        subtree = expand_tree(self.tree, node, batch, self.task, guarded)
        self.never_expand(guard_nodes(subtree, guarded))
        self.hooks.new_subtree(subtree, batch, literal, state)
        return subtree

    def increase_priority(self, subtree: Fallback) -> Resolution:
        """Algorithm 1, lines 11-12: IncreasePriority while the tree is in conflict."""
        return resolve_conflicts(self.tree, subtree, self.judge(), self.options.reorder_goals,
                                 self.options.refine_more)

    def _unexpand(self, subtree: Fallback, condition: Node) -> None:
        """Undo ExpandTree: put the condition back where its atomic BT stands."""
        subtree.remove(condition)
        parent = subtree.parent
        if parent is None:
            self.tree.root = condition
            return
        parent.replace(subtree, condition)

    def memory(self) -> LoopMemory:
        """What this loop knows of its tree (to go on from it elsewhere: `resume`)."""
        return LoopMemory(frozenset(self.expanded), frozenset(self.dead),
                          frozenset(self._guards_seen), dict(self.grounding))

    def resume(self, tree: BehaviorTree, memory: LoopMemory) -> None:
        """Act on `tree`, grown elsewhere (offline planning), from here on. The tree object
        stays the same (its recorders stay attached); its root becomes `tree`'s."""
        self.tree.halt(self.skills)
        self.tree.root = tree.root
        self.expanded = set(memory.expanded)
        self.dead = set(memory.dead)
        self._guards_seen = set(memory.guards)
        self.ground(memory.grounding.values())
        self._judged = None
        self._circles.forget()
        self._stalls = 0

    # --- what departures and helpers call ----------------------------------------------

    def achievers(self, node: Node, literal: GroundLiteral,
                  state: frozenset[Atom]) -> tuple[list[GroundAction], list[GroundAction]]:
        """The ranked achievers of `node`'s condition, and the spare ones (choice.py)."""
        kept, spare, circular = achievers_for(self, node, literal, state,
                                              self.hooks.rank_achievers)
        if circular:
            self.circular.add(literal)
        return kept, spare

    def expand_now(self, report: TickReport, node: Node, state: frozenset[Atom],
                   found: tuple[list[GroundAction], list[GroundAction]] | None = None
                   ) -> bool:
        """Expand `node` before a tick reaches it (btplan.acting.early), as that tick
        would; False when it is left for later (`found`: its achievers, if known)."""
        literal = literal_of(node)
        if literal is None or node in self.expanded or not attached(node, self.tree.root):
            return False
        achievers, spare = found if found is not None else self.achievers(node, literal,
                                                                          state)
        if not achievers:
            return False
        try:
            expansion = self.apply(node, literal, achievers, spare)
        except UnresolvableConflictError:
            return False
        self.expanded.add(node)
        report.add(expansion)
        return True

    def record(
        self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int, moves: int
    ) -> Expansion:
        """Count an expansion of `literal` made by `achievers`."""
        expansion = Expansion(self.ticks, str(literal), [str(a) for a in achievers], conflicts,
                              moves)
        self._tally[literal] += 1
        self.expansions.append(expansion)
        self.started_before_expansion = self.skills.starts
        return expansion

    def ground(self, actions: Iterable[GroundAction]) -> None:
        """The grounded actions the tree's new leaves stand for."""
        for action in actions:
            self.grounding[action.key] = action

    def never_expand(self, nodes: list[Node]) -> None:
        """Guards say what an alternative is for; they are checked, never achieved."""
        self.expanded.update(nodes)
        self.dead.update(nodes)
        self._guards_seen.update(nodes)

    def adopt(self, steps: list[GroundAction], checks: list[Node]) -> None:
        """A plan found by search was put into the tree: ground its steps, never expand
        the checks it brings."""
        self.ground(steps)
        self.expanded.update(checks)
        self.dead.update(checks)
        self.searches += 1

    def narrow_to(self, part: Node) -> None:
        """Act on `part`, a subtree of the tree, as the whole tree from here on: its nodes,
        their statuses and what was expanded in them stay; the rest is halted and dropped."""
        self.tree.narrow_to(part, self.skills)

    def adopt_plan(self, steps: list[GroundAction]) -> None:
        """Put a plan for the whole goal behind the goal tree (`plan_whole_goal`)."""
        adopt_plan(self, steps)

    def judge(self) -> Judge:
        """What conflict checks know now; kept until a guard is added (guards are only
        added: their number tells) or the state changes. Copying the guards grew with
        the tree."""
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

    def most_expanded(self, count: int = 3) -> str:
        """The conditions expanded most often, `on(a, b) (7)`: where the search went round."""
        return most_expanded(self.expansions, count)

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
        """Whether every goal literal holds in the world now: the tree's SUCCESS alone is not
        trusted, since a later action in the same tick may have undone a goal."""
        state = self.world.facts()
        return all(g.holds(state) for g in self.task.goal_literals)

    # --- many ticks (offline planning's rounds) ------------------------------------------

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
