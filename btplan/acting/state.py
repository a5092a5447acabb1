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
    reached: bool
    ticks: int
    expansions: list[Expansion]
    tree: BehaviorTree
    reason: str


class LoopState(Protocol):
    """The loop as its departures and helpers see it (BlendedLoop has all of this).

    They read these fields and change the loop only through its methods."""

    @property
    def task(self) -> Task: ...

    @property
    def world(self) -> PlanningWorld:
        """`Skills` over the robot: the state, refinement, and the skills' logs."""
        ...

    @property
    def options(self) -> PlannerOptions: ...

    @property
    def index(self) -> AchieverIndex: ...

    @property
    def tree(self) -> BehaviorTree: ...

    @property
    def grounding(self) -> Mapping[LeafKey, GroundAction]: ...

    @property
    def expansions(self) -> Sequence[Expansion]: ...

    @property
    def expanded(self) -> Collection[Node]:
        """Conditions expanded (or never to be: guards, checks)."""
        ...

    @property
    def dead(self) -> Collection[Node]:
        """Conditions never to be re-expanded."""
        ...

    @property
    def banned(self) -> frozenset[Choice]: ...

    @property
    def early(self) -> EarlyQueue:
        """Conditions to expand in this tick before a tick reaches them (btplan.acting.early)."""
        ...

    @property
    def deadline(self) -> float | None: ...

    def record(self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int,
               moves: int) -> Expansion: ...

    def apply(self, node: Node, literal: GroundLiteral, achievers: list[GroundAction],
              spare: list[GroundAction] | None = None) -> Expansion: ...

    def achievers(self, node: Node, literal: GroundLiteral,
                  state: frozenset[Atom]) -> tuple[list[GroundAction], list[GroundAction]]: ...

    def expand_now(self, report: TickReport, node: Node, state: frozenset[Atom],
                   found: tuple[list[GroundAction], list[GroundAction]] | None = None
                   ) -> bool: ...

    def judge(self) -> Judge: ...

    def never_expand(self, nodes: list[Node]) -> None: ...

    def ground(self, actions: Iterable[GroundAction]) -> None: ...

    def adopt(self, steps: list[GroundAction], checks: list[Node]) -> None: ...


class EarlyQueue(Protocol):
    """The early expansions' queue, as departures add to it."""

    def replace(self, nodes: list[Node]) -> None: ...

    def extend(self, nodes: list[Node]) -> None: ...

    def expand_broken(self, report: TickReport, last: frozenset[Atom]) -> None: ...

    def expand_if_forced(self, report: TickReport, nodes: list[Node]) -> None: ...
