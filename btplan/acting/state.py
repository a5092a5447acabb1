"""What the acting loop reports, and what its parts share of it.

The loop (btplan.acting.loop) is split by responsibility: choosing achievers
(`choice`), expanding before a tick reaches a condition (`early`), re-expanding
(`regrow`), the last-resort search (`searched`), the messages (`diagnosis`); with the
other goals in view, ranking (`credit`) and setting up another goal's step (`prepare`);
finishing a halted action first (`finish`); the `protect_goals` guards (`protect`).
Those parts see the loop through `LoopState`, so that none of them imports the loop
itself.
"""

from __future__ import annotations

from btplan.bt import BehaviorTree, LeafKey, Node, Status
from btplan.model import GroundAction, GroundLiteral, Task
from btplan.planner import AchieverIndex, Judge, PlannerOptions, PlanningWorld
from btplan.records import field, record

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

if TYPE_CHECKING:
    from btplan.planner.backjump import Choice
    from btplan.planner.rescue import Rescuer


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
    """Conditions looked at ahead of the running actions (btplan.acting.watch), besides
    those the tick itself checked: monitoring, not planning."""


@record
class RunResult:
    reached: bool
    ticks: int
    expansions: list[Expansion]
    tree: BehaviorTree
    reason: str


class LoopState(Protocol):
    """The loop as its parts see it (BlendedLoop has all of this)."""

    task: Task
    world: PlanningWorld
    options: PlannerOptions
    index: AchieverIndex
    tree: BehaviorTree
    grounding: dict[LeafKey, GroundAction]
    expansions: list[Expansion]
    expanded: set[Node]
    """Conditions expanded (or never to be: guards, checks)."""
    dead: set[Node]
    """Conditions never to be re-expanded."""
    circular: set[GroundLiteral]
    banned: frozenset[Choice]
    ahead: list[Node]
    """Later false preconditions waiting to be expanded in this tick (btplan.acting.ahead)."""
    forcing: list[Node]
    """Later false preconditions to expand in this tick only if their achiever would make
    the robot give up what is held before them (`look_deeper`, btplan.acting.ahead)."""
    goal_credit: bool
    optional: set[Node]
    """Conditions added before an achiever for another goal's step (btplan.acting.prepare)."""
    relaxed_plans: object | None
    """btplan.acting.prepare's RelaxedPlans for the index's relaxed model, once asked
    (typed loosely: that module sees the loop through this one)."""
    rescuer: Rescuer | None
    deadline: float | None
    searches: int

    def record(self, literal: GroundLiteral, achievers: list[GroundAction], conflicts: int,
               moves: int) -> Expansion: ...

    def apply(self, node: Node, literal: GroundLiteral, achievers: list[GroundAction],
              spare: list[GroundAction] | None = None) -> Expansion: ...

    def judge(self) -> Judge: ...

    def never_expand(self, nodes: list[Node]) -> None: ...

