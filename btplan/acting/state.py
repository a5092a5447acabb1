"""What the acting loop reports, and how its parts and departures see it.

The loop (btplan.acting.loop) is Algorithm 1; choosing achievers (`choice`), the
early expansions (`early`) and the messages (`diagnosis`) are its own parts, and the
departures from the paper live in btplan.acting.departures behind the hooks of
btplan.acting.hooks. All of them see the loop through `LoopState`, so that none of
them imports the loop itself, and change it only through its methods.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable, Mapping, Sequence

from btplan.bt import BehaviorTree, LeafKey, Node, Status
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.planner import AchieverIndex, Judge, PlannerOptions, PlanningWorld
from btplan.records import field, record

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

if TYPE_CHECKING:
    from btplan.planner.backjump import Choice


@record
class Expansion:
    """One run of ExpandTree: which condition, by which actions, and how it was placed."""

    tick: int
    condition: str
    achievers: list[str]
    conflicts_resolved: int
    moves: int


@record
class TickReport:
    """What one tick of the loop did: its status, the expansions made in it, and the
    planning and monitoring it cost."""

    tick: int
    status: Status
    expansions: list[Expansion] = field(default_factory=list)
    planning_seconds: float = 0.0
    """CPU time (process time) spent growing the tree in this tick, the tick itself excluded."""
    checks_ahead: int = 0
    """Conditions looked at ahead of the running actions (btplan.acting.departures.watch),
    besides those the tick itself checked: monitoring, not planning."""

    def add(self, expansion: Expansion) -> None:
        """An expansion made in this tick."""
        self.expansions.append(expansion)

    def add_planning(self, seconds: float) -> None:
        """CPU seconds spent growing the tree in this tick."""
        self.planning_seconds += seconds

    def follows(self, earlier: TickReport) -> None:
        """The expansions and planning time of `earlier` (planning before the tick) come
        first in this tick's report."""
        self.expansions[:0] = earlier.expansions
        self.planning_seconds += earlier.planning_seconds

    def looked_ahead(self, checks: int) -> None:
        """Conditions looked at ahead of the running actions in this tick."""
        self.checks_ahead = checks


@record(frozen=True)
class LoopMemory:
    """What a loop knows of its tree beyond the tree itself: which conditions it expanded,
    which it must never expand (guards, checks), the grounded actions of the leaves. A
    tree planned offline comes with it, so that a loop acting online goes on from it."""

    expanded: frozenset[Node]
    dead: frozenset[Node]
    guards: frozenset[Node]
    grounding: Mapping[LeafKey, GroundAction]


@record
class RunResult:
    """How `BlendedLoop.run` ended: reached or not, after how many ticks and expansions,
    the tree, and why."""

    reached: bool
    ticks: int
    expansions: list[Expansion]
    tree: BehaviorTree
    reason: str


class LoopState(Protocol):
    """The loop as its departures and helpers see it (BlendedLoop has all of this).

    They read these fields and change the loop only through its methods."""

    @property
    def task(self) -> Task:
        """The task the loop plans for."""
        ...

    @property
    def world(self) -> PlanningWorld:
        """`Skills` over the robot: the state, refinement, and the skills' logs."""
        ...

    @property
    def options(self) -> PlannerOptions:
        """How conditions are expanded (achiever ranking, conflicts, budgets)."""
        ...

    @property
    def index(self) -> AchieverIndex:
        """The task's achievers, relaxed model and mutexes, built once."""
        ...

    @property
    def tree(self) -> BehaviorTree:
        """The tree as it has grown; departures read it, the loop's methods change it."""
        ...

    @property
    def grounding(self) -> Mapping[LeafKey, GroundAction]:
        """The grounded action each action leaf stands for, by its key."""
        ...

    @property
    def expansions(self) -> Sequence[Expansion]:
        """Every expansion made so far, in order."""
        ...

    @property
    def expanded(self) -> Collection[Node]:
        """Conditions expanded (or never to be: guards, checks)."""
        ...

    @property
    def dead(self) -> Collection[Node]:
        """Conditions never to be re-expanded."""
        ...

    @property
    def banned(self) -> frozenset[Choice]:
        """(condition, action) choices never to use (btplan.planner.backjump)."""
        ...

    @property
    def early(self) -> EarlyQueue:
        """Conditions to expand in this tick before a tick reaches them (btplan.acting.early)."""
        ...

    @property
    def deadline(self) -> float | None:
        """A time.perf_counter() value the last-resort search must not run past."""
        ...

    def record(self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int,
               moves: int) -> Expansion:
        """Count an expansion of `literal` made by `achievers` (for a departure that grew
        the tree its own way)."""
        ...

    def apply(self, node: Node, literal: GroundLiteral, achievers: list[GroundAction],
              spare: list[GroundAction] | None = None) -> Expansion:
        """ExpandTree (Algorithm 2) of `node` with `achievers`, then IncreasePriority
        while it conflicts; `spare`: achievers to try when those conflict everywhere."""
        ...

    def achievers(self, node: Node, literal: GroundLiteral,
                  state: frozenset[Atom]) -> tuple[list[GroundAction], list[GroundAction]]:
        """The ranked achievers of `node`'s condition in `state`, and the spare ones."""
        ...

    def expand_now(self, report: TickReport, node: Node, state: frozenset[Atom],
                   found: tuple[list[GroundAction], list[GroundAction]] | None = None
                   ) -> bool:
        """Expand `node` before a tick reaches it, as that tick would; False when it is
        left for later (`found`: its achievers, if known)."""
        ...

    def judge(self) -> Judge:
        """What conflict checks know now (the grounding, the guards, the mutexes)."""
        ...

    def never_expand(self, nodes: list[Node]) -> None:
        """Conditions to check and never achieve (guards of an alternative)."""
        ...

    def ground(self, actions: Iterable[GroundAction]) -> None:
        """The grounded actions the tree's new leaves stand for."""
        ...

    def adopt(self, steps: list[GroundAction], checks: list[Node]) -> None:
        """A plan found by search was put into the tree: ground its steps, never expand
        the checks it brings."""
        ...

    def narrow_to(self, part: Node) -> None:
        """Act on `part`, a subtree of the tree, as the whole tree from here on."""
        ...


class EarlyQueue(Protocol):
    """The early expansions' queue, as departures add to it."""

    def replace(self, nodes: list[Node]) -> None:
        """These, instead of what waited (a new expansion's later preconditions)."""
        ...

    def extend(self, nodes: list[Node]) -> None:
        """These too, after what waits."""
        ...

    def expand_broken(self, report: TickReport, last: frozenset[Atom]) -> None:
        """Expand the conditions ahead of the running actions that held in `last` and an
        outside change made false."""
        ...

    def expand_if_forced(self, report: TickReport, nodes: list[Node]) -> None:
        """Of the later false preconditions `nodes`, expand those the robot could not
        reach later without giving up what it holds."""
        ...
