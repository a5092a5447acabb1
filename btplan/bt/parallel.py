"""Parallel with a success threshold, ticking its children in one tick (BT.CPP ParallelNode).

Every tick, each child that has not finished yet is ticked, left to right. A child
that returns SUCCESS or FAILURE is remembered as finished and not ticked again until
the node itself finishes. After each child the counts are checked:
  - `success` children succeeded: halt the ones still RUNNING, return SUCCESS;
  - `failure` children failed, or too few are left to reach `success`: halt the
    running ones, return FAILURE;
  - otherwise, once every child was visited: RUNNING.
A threshold below zero counts from the number of children (-1 means all of them), as
in BT.CPP, so `Parallel(children, success=-1)` succeeds when all succeed.
"""

from __future__ import annotations

from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.world import World


class Parallel(Composite):
    """Ticks every unfinished child each tick; decides by success and failure counts."""

    __slots__ = ("_done", "_failures", "_successes", "failure", "success")
    kind = "Parallel"

    def __init__(
        self,
        children: list[Node] | None = None,
        success: int = -1,
        failure: int = 1,
        name: str = "",
    ) -> None:
        super().__init__(children, name)
        self.success = success
        self.failure = failure
        self._done: set[int] = set()
        self._successes = 0
        self._failures = 0

    def _threshold(self, value: int) -> int:
        n = len(self.children)
        return n + value + 1 if value < 0 else value

    def tick(self, world: World) -> Status:
        """Tick the unfinished children and decide by the counts (see the module). A success
        threshold above the number of children could never be met: ValueError."""
        children = self.children
        need_success = self._threshold(self.success)
        need_failure = self._threshold(self.failure)
        if need_success > len(children):
            raise ValueError(
                f"Parallel {self.name!r}: success threshold {need_success} "
                f"exceeds its {len(children)} children")
        for i, child in enumerate(children):
            if i in self._done:
                continue
            status = child.tick(world)
            if status is SUCCESS:
                self._done.add(i)
                self._successes += 1
            elif status is FAILURE:
                self._done.add(i)
                self._failures += 1
            if self._successes >= need_success:
                return self._finish(SUCCESS, world)
            if (self._failures >= need_failure
                    or len(children) - self._failures < need_success):
                return self._finish(FAILURE, world)
        self.status = RUNNING
        return RUNNING

    def _finish(self, status: Status, world: World) -> Status:
        for child in self.children:
            if child.status is RUNNING:
                child.halt(world)
        self._reset()
        self.status = status
        return status

    def _reset(self) -> None:
        self._done = set()
        self._successes = self._failures = 0

    def halt(self, world: World) -> None:
        """Forget which children finished and the counts, so the next tick starts a fresh run;
        then halt the children."""
        self._reset()
        super().halt(world)


__all__ = ["Parallel"]
