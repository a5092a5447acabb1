"""BT.CPP's own Sequence, Fallback and Parallel, as trees read from its XML need them.

They tick like btplan's composites and differ only where SKIPPED (BT.CPP 4's
`_skipIf`/`_while`) comes in: skipped children are counted, a node whose children were
all skipped answers SKIPPED, and a decision resets the other children the way BT.CPP's
resetChildren does. btplan's own composites, which the planner builds and the acting
loop ticks, keep that count out of their loop.
"""

from __future__ import annotations

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.node import Composite, Node
from btplan.bt.parallel import Parallel
from btplan.bt.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.world import World


def reset_children(node: Composite, world: World) -> None:
    """Halt the children still active, as BT.CPP's resetChildren does on completion."""
    for child in node.children:
        if child.status is not IDLE:
            child.halt(world)


def _counting_tick(node: BtcppSequence | BtcppFallback, world: World) -> Status:
    """BT.CPP's Sequence/Fallback loop, also counting SKIPPED children: when every child
    of a run was skipped, the node answers SKIPPED (and, as BT.CPP, stays RUNNING).

    As BT.CPP's resetChildren, a decision halts every other child still marked
    RUNNING, which includes a composite that answered SKIPPED on an earlier tick.
    """
    children = node.children
    stop_on = node.stop_on
    start = node._current if node.memory else 0
    if start == 0:
        node.skipped = 0
    for i in range(start, len(children)):
        status = children[i].tick(world)
        if status is RUNNING or status is stop_on:
            left_too = status is not RUNNING or not node.memory
            for j, other in enumerate(children):
                if (j > i and other.status is not IDLE
                        or j < i and left_too and other.status is RUNNING):
                    other.halt(world)
            node._current = i if status is RUNNING else 0
            node.status = status
            return status
        if status is SKIPPED:
            node.skipped += 1
    node._current = 0
    if node.skipped == len(children):
        node.status = RUNNING
        return SKIPPED
    reset_children(node, world)
    node.status = status = SUCCESS if stop_on is FAILURE else FAILURE
    return status


class BtcppSequence(Sequence):
    """A Sequence read from BT.CPP XML: the same ticks, plus SKIPPED when all children
    were skipped (btplan's own Sequence leaves that count out of its hot loop)."""

    __slots__ = ("skipped",)

    def __init__(self, children: list[Node] | None = None, name: str = "",
                 memory: bool = False) -> None:
        super().__init__(children, name, memory)
        self.skipped = 0

    def tick(self, world: World) -> Status:
        """Sequence's tick with BT.CPP's SKIPPED rules (`_counting_tick`): SKIPPED when every
        child was skipped, and a decision halts the other children still active."""
        return _counting_tick(self, world)


class BtcppFallback(Fallback):
    """A Fallback read from BT.CPP XML: the same ticks, plus SKIPPED when all children
    were skipped."""

    __slots__ = ("skipped",)

    def __init__(self, children: list[Node] | None = None, name: str = "",
                 memory: bool = False) -> None:
        super().__init__(children, name, memory)
        self.skipped = 0

    def tick(self, world: World) -> Status:
        """Fallback's tick with BT.CPP's SKIPPED rules (`_counting_tick`): SKIPPED when every
        child was skipped, and a decision halts the other children still active."""
        return _counting_tick(self, world)


class BtcppParallel(Parallel):
    """A Parallel read from BT.CPP XML: SKIPPED children count as BT.CPP 4.8 counts them.

    A skipped child counts towards success when the success threshold is relative
    (negative); when every child was skipped the node answers SKIPPED.
    """

    __slots__ = ()

    def tick(self, world: World) -> Status:
        """Parallel's tick, except that a SKIPPED child is not finished (it is ticked again next
        tick) and counts towards a negative success threshold; SKIPPED when every child was
        skipped. A decision halts every child that is not idle."""
        children = self.children
        need_success = self._threshold(self.success)
        need_failure = self._threshold(self.failure)
        skipped = 0
        for i, child in enumerate(children):
            if i not in self._done:
                status = child.tick(world)
                if status is SKIPPED:
                    skipped += 1
                elif status is SUCCESS or status is FAILURE:
                    self._done.add(i)
                    if status is SUCCESS:
                        self._successes += 1
                    else:
                        self._failures += 1
            if (self._successes >= need_success
                    or self.success < 0 and self._successes + skipped >= need_success):
                self._reset()
                reset_children(self, world)
                self.status = SUCCESS
                return SUCCESS
            if (len(children) - self._failures < need_success
                    or self._failures == need_failure):
                self._reset()
                reset_children(self, world)
                self.status = FAILURE
                return FAILURE
        self.status = RUNNING
        return SKIPPED if skipped == len(children) else RUNNING



__all__ = ["BtcppFallback", "BtcppParallel", "BtcppSequence", "reset_children"]
