"""Algorithm 1 as an acting loop: tick the tree against a world, expand it when it fails.

The tree is never rebuilt: it starts as the goal conditions and only grows, one atomic
BT per failing tick, with conflicts resolved right after each expansion. All world
access of planning lives here; the planner steps in btplan.planner are plain functions.
"""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field

from btplan.acting.ahead import attached, later_false
from btplan.acting.scope import lineage, scope_moved
from btplan.bt import (
    FAILURE,
    SUCCESS,
    Action,
    BehaviorTree,
    Composite,
    Fallback,
    LeafKey,
    Node,
    Status,
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
from btplan.planner.achievers import ALL, guards
from btplan.planner.backjump import Choice, conflict_choices, enclosing_choices, running_choices
from btplan.planner.conflicts import achiever_leaves, alternative_conflicts
from btplan.planner.expand import (
    achiever_sequence,
    condition_node,
    conditions_bfs,
    goal_check,
    guard_nodes,
    non_circular,
    not_through_pursued,
    pursued,
)
from btplan.planner.lookahead import closest_first, keep_reachable, needed_later
from btplan.planner.protect import white_knights
from btplan.planner.agenda import goal_agenda, state_orders
from btplan.planner.rescue import Rescuer, plan_whole_goal

STUCK_EXPANSIONS = 8
"""Expansions of one condition after which it counts as stuck (for `search_stuck`)."""

ROUND_EXPANSIONS = 40
"""Expansions of one condition after which the attempt stops: it goes round, and the
next strategy (or the last-resort search) is better spent time than the budget. A task
with more objects allows one expansion per object: gripper's robot must be in a room
again for every ball, blocksworld's hand empty again for every block moved."""

BACKTRACKS = 2
"""Further batches of achievers tried when the first has no conflict-free place."""


def _unexpand(tree: BehaviorTree, subtree: Fallback, condition: Node) -> None:
    """Undo ExpandTree: put the condition back where its atomic BT stands."""
    subtree.remove(condition)
    parent = subtree.parent
    if parent is None:
        tree.root = condition
        return
    parent.replace(subtree, condition)


@dataclass
class Expansion:
    """One run of ExpandTree: which condition, by which actions, and how it was placed."""

    tick: int
    condition: str
    achievers: list[str]
    conflicts_resolved: int
    moves: int


@dataclass
class TickReport:
    tick: int
    status: Status
    expansions: list[Expansion] = field(default_factory=list)
    planning_seconds: float = 0.0
    """CPU time (process time) spent growing the tree in this tick, the tick itself excluded."""


@dataclass
class RunResult:
    reached: bool
    ticks: int
    expansions: list[Expansion]
    tree: BehaviorTree
    reason: str


class BlendedLoop:
    """Plans and acts at once (the paper's Algorithm 1) against any PlanningWorld.

    `tick()` ticks once; on FAILURE it expands the first failed condition found
    breadth first (Algorithm 3), substitutes its atomic BT (Algorithm 2) and moves it
    until no conflict is left. A condition without achievers is skipped in favour of
    the next failed one; if none has achievers, NoAchieverError names them. When the
    world comes back to a state it was in, with no expansion in between and no
    outside change, the loop is going round in circles: NoProgressError. An outside
    change is one seen between two ticks, or one a world counts in `outside_changes`
    (agents that act while the robot does, as in the PyBullet world). In a `continuous`
    world, where facts change while an action runs (a robot driving past a cube), states
    are compared only on ticks where an action ended: passing by the same place twice
    within one action is not a loop, and a loop of actions still repeats its states there.
    """

    def __init__(
        self,
        task: Task,
        world: PlanningWorld,
        options: PlannerOptions | None = None,
        like: AchieverIndex | None = None,
        look_ahead: bool = False,
        banned: frozenset[Choice] = frozenset(),
        scope_moves: bool = False,
    ) -> None:
        """`like`: an index of the same task to share models with; `look_ahead`: also
        expand, in the same tick, the later preconditions that are false (btplan.acting.ahead);
        `banned`: (condition, action) choices never used (btplan.planner.backjump);
        `scope_moves`: skip a moved subtree while what it was moved for holds
        (btplan.acting.scope)."""
        self.banned = banned
        self.culprits: list[Choice] = []
        """When planning stopped: the achiever choices to give up first (backjump.py)."""
        self.task = task
        self.look_ahead = look_ahead
        self.scope_moves = scope_moves
        self._ahead: list[Node] = []
        self.world = world
        self.options = options or PlannerOptions()
        self.index = AchieverIndex(task, self.options, like)
        order = None
        if self.options.goal_agenda and self.options.mutexes and len(task.goal_literals) > 1:
            relaxed = self.index.relaxed
            extra = state_orders(task.goal_literals, self.index.mutexes, relaxed,
                                 task.initial_state) if self.options.state_agenda else None
            order = goal_agenda(task.goal_literals, relaxed.producers, self.index.mutexes,
                                extra)
        self.tree = initial_tree(task, order)
        self.grounding: dict[LeafKey, GroundAction] = {}
        self.expansions: list[Expansion] = []
        self.ticks = 0
        self._expanded: set[Node] = set()
        self._dead: set[Node] = set()
        self._guards_seen: set[Node] = set()
        self._circular: set[GroundLiteral] = set()
        self._seen: set[tuple[frozenset[Atom], int]] = set()
        self._last_state: frozenset[Atom] | None = None
        self._outside = 0
        self._ended = 0
        self._stalls = 0
        self.premature_successes = 0
        self.searches = 0
        """Stuck conditions planned by the last-resort search (`search_stuck`)."""
        self.deadline: float | None = None
        """A time.perf_counter() value the last-resort search must not run past."""
        self._rescuer: Rescuer | None = None
        self._tally: Counter[GroundLiteral] = Counter()
        self._round_limit = max(ROUND_EXPANSIONS, len(task.object_types))
        check = goal_check(self.tree)
        if check is not None:  # the final re-check of the goals is never expanded
            self._expanded.update(check.children)
            self._dead.update(check.children)

    def use_world(self, world: PlanningWorld) -> None:
        """Keep the tree and continue against another world (a fresh run from the start)."""
        self.tree.halt(self.world)
        self.world = world
        self._seen.clear()
        self._last_state = None
        self._stalls = 0

    # --- one tick ----------------------------------------------------------------------

    def tick(self) -> TickReport:
        before = self.world.facts()
        if before != self._last_state:
            self._seen.clear()  # an outside change: a repeated state is no longer a loop
        self.ticks += 1
        report = TickReport(self.ticks, FAILURE)
        while True:
            status = report.status = self.tree.tick(self.world)
            if status is not FAILURE:
                self._stalls = 0
                break
            started = time.process_time()
            try:
                expansion = self._expand()
                if expansion is not None:
                    report.expansions.append(expansion)
                    self._expand_ahead(report)
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
        after = self.world.facts()
        outside = int(getattr(self.world, "outside_changes", 0))
        if outside != self._outside:
            # Someone else acted while the tree ticked (a world whose agents move at
            # the same time as the robot): a repeated state is no longer a loop.
            self._outside = outside
            self._seen.clear()
        ended = _actions_ended(self.world)
        boundary = ended != self._ended or not getattr(self.world, "continuous", False)
        self._ended = ended
        if after != before and boundary:
            key = (after, len(self.expansions))
            if key in self._seen:
                executed = getattr(self.world, "executed", [])
                if executed:  # the same state under the same tree: drop what ran in the loop
                    self.culprits = running_choices(self.tree.root, executed[-1].key)
                raise NoProgressError(self._loop_reason())
            self._seen.add(key)
        self._last_state = after
        return report

    def _expand(self) -> Expansion | None:
        state = self.world.facts()
        missing: list[GroundLiteral] = []
        stuck: list[Node] = []
        failed = failed_conditions(self.tree, self._expanded)
        if self.options.closest_first and len(failed) > 1:
            failed = closest_first(failed, self.index.relaxed, state)
        for node in failed:
            literal = literal_of(node)
            assert literal is not None
            if self._tally[literal] >= STUCK_EXPANSIONS:
                searched = self._search(node)  # expanded again and again: going round
                if searched is not None:
                    return searched
                if self._tally[literal] >= self._round_limit and self.options.refine_more:
                    self.culprits = enclosing_choices(node)
                    raise NoProgressError(
                        f"{literal} was expanded {self._tally[literal]} times: the tree goes "
                        f"round (expanded most often: {self.most_expanded()})")
            achievers, spare = self._achievers(node, literal, state)
            self._expanded.add(node)
            if not achievers:
                self._dead.add(node)
                missing.append(literal)
                stuck.append(node)
                continue
            if self.look_ahead:  # before ExpandTree moves the node under a Fallback
                self._ahead = later_false(node, state, self._expanded)
            return self._apply(node, literal, achievers, spare)
        more = self._reexpand(state) if self.options.refine_more else None
        if more is not None:
            return more
        for node in stuck:
            searched = self._search(node)
            if searched is not None:
                return searched
        if missing:
            self.culprits = list(dict.fromkeys(c for n in stuck for c in enclosing_choices(n)))
            raise NoAchieverError(self._no_achiever_reason(missing))
        return None

    def _expand_ahead(self, report: TickReport) -> None:
        """Expand the false preconditions after the one just expanded, as the tick would
        once the robot had achieved that one; a condition without a conflict-free place
        now is left for the tick to find."""
        pending, self._ahead = self._ahead, []
        state = self.world.facts()
        for node in pending:
            if (len(report.expansions) >= self.options.expansions_per_tick
                    or len(self.expansions) >= self.options.max_expansions):
                return
            literal = literal_of(node)
            if (literal is None or node in self._expanded or literal.holds(state)
                    or not attached(node, self.tree.root)):
                continue
            achievers, spare = self._achievers(node, literal, state)
            if not achievers:
                continue
            try:
                expansion = self._apply(node, literal, achievers, spare)
            except UnresolvableConflictError:
                continue
            self._expanded.add(node)
            report.expansions.append(expansion)

    def _achievers(
        self, node: Node, literal: GroundLiteral, state: frozenset[Atom]
    ) -> tuple[list[GroundAction], list[GroundAction]]:
        """Ranked achievers of a failed condition, without circular or dead-end ones,
        and the ranked candidates left over (for backtracking)."""
        width = self.options.max_alternatives
        if not self.options.avoid_dead_ends:
            achievers = self.index.achievers(literal, state, self.world.refine,
                                             ALL if self.banned else None)
            allowed = self._allowed(self._non_circular(achievers, node, literal), literal)
            return allowed[:width], []
        # Rank every candidate, so that dropping dead ends still leaves `width` of them.
        achievers = self.index.achievers(literal, state, self.world.refine, ALL)
        achievers = self._allowed(self._non_circular(achievers, node, literal), literal)
        kept = keep_reachable(achievers, needed_later(node), self.index.relaxed, state, width)
        chosen = {a.key for a in kept}  # keys: comparing whole actions is slow
        return kept, [a for a in achievers if a.key not in chosen]

    def _allowed(self, achievers: list[GroundAction], literal: GroundLiteral) -> list[GroundAction]:
        """Achievers not banned for this condition by an earlier attempt."""
        if not self.banned:
            return achievers
        return [a for a in achievers if (literal, a.key) not in self.banned]

    def _non_circular(
        self, achievers: list[GroundAction], node: Node, literal: GroundLiteral
    ) -> list[GroundAction]:
        """Drop circular achievers (with refine_more), remembering when that left none."""
        if not self.options.refine_more:
            return achievers
        kept = non_circular(achievers, pursued(node))
        if achievers and not kept:
            self._circular.add(literal)
        return kept

    def _no_achiever_reason(self, missing: list[GroundLiteral]) -> str:
        """Say which kind of dead end it is: no achiever at all, or none from here."""
        never = sorted({str(c) for c in missing if not self.index.has_effect(c)})
        circular = sorted({str(c) for c in missing if c in self._circular})
        lost = sorted({str(c) for c in missing
                       if self.index.has_effect(c) and c not in self._circular})
        parts = []
        if circular:
            parts.append(
                f"stuck after {len(self.expansions)} expansions: every achiever of "
                + " or ".join(circular) + " needs a condition that an enclosing fallback is"
                " already trying to achieve (the tree chose an order it cannot complete;"
                " the search, not the domain, is at fault)")
        if never:
            parts.append("no action of the domain can make " + " or ".join(never) + " hold")
        if lost:
            recent = [str(a) for a in getattr(self.world, "executed", [])[-4:]]
            parts.append(
                f"stuck after {len(self.expansions)} expansions: no action can make "
                + " or ".join(lost) + " hold from the state the tree led to (every achiever"
                " needs something that can no longer be brought about, even ignoring deletes)"
                + (f"; last actions: {', '.join(recent)}" if recent else "")
            )
        return "; ".join(parts)

    def most_expanded(self, count: int = 3) -> str:
        """The conditions expanded most often, `on(a, b) (7)`: where the search went round."""
        tally = Counter(e.condition for e in self.expansions)
        return ", ".join(f"{c} ({n})" for c, n in tally.most_common(count))

    def _reexpand(self, state: frozenset[Atom]) -> Expansion | None:
        """Give a failed, already expanded condition the achievers that apply now.

        Refinement depends on the state (the paper's RefineActions), so the achievers
        chosen when a condition was first expanded may not fit the state it fails in
        later. Appending alternatives keeps the tree growing, never rebuilt.
        """
        for node in conditions_bfs(self.tree.root):
            fallback = node.parent
            if (node.status is not FAILURE or node not in self._expanded or node in self._dead
                    or not isinstance(fallback, Fallback) or fallback.children[0] is not node
                    or fallback.status is not FAILURE):
                continue
            literal = literal_of(node)
            assert literal is not None
            present = {leaf.key for leaf in achiever_leaves(fallback)}
            limit = len(present) + self.options.max_alternatives
            found = self.index.achievers(literal, state, self.world.refine, limit)
            goals = pursued(node)
            fresh = [a for a in self._allowed(non_circular(found, goals), literal)
                     if a.key not in present]
            fresh = not_through_pursued(fresh, goals, self.index.relaxed, state,
                                        self.task.object_types)
            if fresh and len(self.expansions) >= self.options.max_expansions:
                raise BudgetExceededError(
                    f"the expansion budget ({self.options.max_expansions}) ran out "
                    f"while {literal} still fails; expanded most often: {self.most_expanded()}"
                )
            grown = self._append_alternatives(fallback, fresh)
            if grown is not None:
                added, conflicts, moves = grown
                return self._record(literal, added, conflicts, moves)
        return None

    def _append_alternatives(
        self, fallback: Fallback, actions: list[GroundAction]
    ) -> tuple[list[GroundAction], int, int] | None:
        """Append achievers to an expanded condition's fallback, as ExpandTree would.

        New alternatives that conflict are dropped if others do not; if all do, the
        fallback is moved like a new subtree (the goal order may have to change now);
        if no place is free of conflicts, nothing is added.
        """
        judge = self._judge()
        appended: list[tuple[GroundAction, Node]] = []
        literal = literal_of(fallback.children[0])
        assert literal is not None
        state = self.world.facts()
        for action in actions[: self.options.max_alternatives]:
            self.grounding[action.key] = action
            guard = guards(action, literal, state)
            alternative = achiever_sequence(action, self.task, guard)
            self._never_expand(alternative.children[: len(guard)])
            fallback.append(alternative)
            appended.append((action, alternative))
        clean = [(a, n) for a, n in appended if not alternative_conflicts(fallback, n, judge)]
        if clean:
            for action, node in appended:
                if (action, node) not in clean:
                    fallback.remove(node)
            return [a for a, _ in clean], 0, 0
        if not appended or not self.options.reorder_goals:
            for _, node in appended:
                fallback.remove(node)
            return None
        try:
            resolution = resolve_conflicts(self.tree, fallback, judge, True, False)
        except UnresolvableConflictError:
            for _, node in appended:
                fallback.remove(node)
            return None
        return [a for a, _ in appended], len(resolution.conflicts), resolution.moves

    def _record(
        self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int, moves: int
    ) -> Expansion:
        expansion = Expansion(self.ticks, str(literal), [str(a) for a in achievers], conflicts,
                              moves)
        self._tally[literal] += 1
        self.expansions.append(expansion)
        return expansion

    def _apply(
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
            self._never_expand(guard_nodes(subtree, guarded))
            if self.options.protect_goals:
                self._protect(subtree)
            before = lineage(subtree) if self.scope_moves else []
            try:
                resolution = resolve_conflicts(
                    self.tree, subtree, self._judge(), self.options.reorder_goals,
                    self.options.refine_more,
                )
            except UnresolvableConflictError as error:
                if first is None:
                    first = error
                    self.culprits = conflict_choices(subtree, self._judge())
                _unexpand(self.tree, subtree, node)
                continue
            if resolution.moves and before:
                self._never_expand(scope_moved(before, self.task))
            return self._record(literal, batch, len(resolution.conflicts), resolution.moves)
        assert first is not None
        searched = self._search(node)
        if searched is not None:
            return searched
        raise first

    @staticmethod
    def _guards(
        actions: list[GroundAction], literal: GroundLiteral, state: frozenset[Atom]
    ) -> dict[LeafKey, tuple[GroundLiteral, ...]]:
        """Guards for the achievers of a wildcard condition (achievers.guards)."""
        return {a.key: g for a in actions if (g := guards(a, literal, state))}

    def _never_expand(self, nodes: list[Node]) -> None:
        """Guards say what an alternative is for; they are checked, never achieved."""
        self._expanded.update(nodes)
        self._dead.update(nodes)
        self._guards_seen.update(nodes)

    def _search(self, node: Node) -> Expansion | None:
        """The last resort (`search_stuck`): plan a stuck condition by search.

        btplan/planner/rescue.py says what is searched for and where the plan goes;
        the checks it adds are never expanded.
        """
        if not self.options.search_stuck:
            return None
        if self._rescuer is None:
            mutexes = self.index.mutexes if self.options.mutexes else None
            self._rescuer = Rescuer(self.task, self.index.subgoal_search, mutexes)
        rescued = self._rescuer.rescue(self.tree, node, self.world.facts(), self.deadline)
        if rescued is None:
            return None
        literal, steps, checks = rescued
        for action in steps:
            self.grounding[action.key] = action
        self._expanded.update([*checks, node])
        self._dead.update([*checks, node])
        self.searches += 1
        return self._record(literal, steps, 0, 0)

    def adopt_plan(self, steps: list[GroundAction]) -> None:
        """Put a plan for the whole goal behind the goal tree (`plan_whole_goal`)."""
        checks = plan_whole_goal(self.tree, self.task, steps)
        for action in steps:
            self.grounding[action.key] = action
        self._expanded.update(checks)
        self._dead.update(checks)
        self.searches += 1

    def _protect(self, subtree: Fallback) -> None:
        """Check, before each new achiever, what keeps the other goals reachable."""
        state = self.world.facts()
        for alternative in subtree.children[1:]:
            last = alternative.children[-1] if alternative.children else None
            if not isinstance(last, Action) or last.key not in self.grounding:
                continue
            action = self.grounding[last.key]
            for atom in white_knights(action, state, self.task.goal_literals,
                                      self.index.relaxed):
                guard = condition_node(GroundLiteral(atom, True), self.task)
                assert isinstance(alternative, Composite)
                alternative.insert(0, guard)

    def _judge(self) -> Judge:
        mutexes = self.index.mutexes if self.options.mutexes else None
        if not self.options.reorder_goals:  # the paper: no circularity check on places
            return Judge(self.grounding, mutexes, frozenset(self._guards_seen))
        return Judge(self.grounding, mutexes, frozenset(self._guards_seen),
                     self.index.relaxed, self.world.facts())

    def _stall(self) -> None:
        """The tree failed with nothing to expand (an action failed): retry, a few times."""
        self._stalls += 1
        if self._stalls > self.options.stall_limit:
            raise NoProgressError(
                f"the tree failed {self._stalls} ticks in a row with no condition left "
                f"to expand; failing actions: {', '.join(self._failing_actions()) or 'none'}"
            )

    def _failing_actions(self) -> list[str]:
        return sorted(
            {n.name for n in self.tree.root.walk() if isinstance(n, Action) and n.status is FAILURE}
        )

    def _loop_reason(self) -> str:
        recent = [str(a) for a in getattr(self.world, "executed", [])[-6:]]
        tail = f"; last actions: {', '.join(recent)}" if recent else ""
        return (
            "the world came back to an earlier state with no new expansion "
            f"(after {len(self.expansions)} expansions){tail}"
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


def _actions_ended(world: object) -> int:
    """How many actions the world has seen end (done, failed or halted), where it logs them."""
    return sum(len(getattr(world, log, ())) for log in ("executed", "failed", "halted"))
