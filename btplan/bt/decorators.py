"""Decorators: one child, one rule that rewrites its status (BT.CPP's decorator nodes).

A decorator is a Composite with at most one child, so the planner can `replace` the
condition under an Inverter exactly as it replaces a child of a Sequence. Every
decorator halts its child when it is halted itself; the ones that end a RUNNING child
early (Timeout) halt it before returning.
"""

from __future__ import annotations

from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.world import World


class Decorator(Composite):
    """A node with exactly one child; ticking it without one is a programming error."""

    __slots__ = ()
    kind = "Decorator"

    def __init__(self, child: Node | None = None, name: str = "") -> None:
        super().__init__([child] if child is not None else [], name)

    @property
    def child(self) -> Node:
        """The one child. A decorator without one raises ValueError naming it: the code that
        built the tree forgot the child."""
        if not self.children:
            raise ValueError(f"decorator {self.name or type(self).__name__!r} has no child")
        return self.children[0]

    def insert(self, index: int, child: Node) -> None:
        """Composite.insert for at most one child: a second raises ValueError. `replace` still
        works, as it removes the old child before inserting the new one."""
        if self.children:
            raise ValueError(f"decorator {self.name or type(self).__name__!r} already has a child")
        super().insert(index, child)


class Inverter(Decorator):
    """SUCCESS becomes FAILURE and FAILURE becomes SUCCESS; RUNNING passes through.

    This is how a negative condition (`not holding(cube)`) appears in a tree.
    """

    __slots__ = ()
    kind = "Inverter"

    def tick(self, world: World) -> Status:
        """Swap the child's SUCCESS and FAILURE; RUNNING and SKIPPED are passed on unchanged."""
        status = self.children[0].tick(world)
        if status is SUCCESS:
            status = FAILURE
        elif status is FAILURE:
            status = SUCCESS
        self.status = status
        return status


class ForceSuccess(Decorator):
    """SUCCESS whether the child succeeded or failed; RUNNING (and SKIPPED) pass through."""

    __slots__ = ()
    kind = "ForceSuccess"

    def tick(self, world: World) -> Status:
        """SUCCESS once the child finishes, either way. A SKIPPED child is passed on and leaves
        the node marked RUNNING, as BT.CPP 4 does."""
        status = self.children[0].tick(world)
        if status is SKIPPED:  # passed on, as in BT.CPP 4
            self.status = RUNNING
            return status
        self.status = status = RUNNING if status is RUNNING else SUCCESS
        return status


class ForceFailure(Decorator):
    """FAILURE whether the child succeeded or failed; RUNNING (and SKIPPED) pass through."""

    __slots__ = ()
    kind = "ForceFailure"

    def tick(self, world: World) -> Status:
        """FAILURE once the child finishes, either way. A SKIPPED child is passed on and leaves
        the node marked RUNNING, as BT.CPP 4 does."""
        status = self.children[0].tick(world)
        if status is SKIPPED:
            self.status = RUNNING
            return status
        self.status = status = RUNNING if status is RUNNING else FAILURE
        return status


class Retry(Decorator):
    """Gives a failing child up to `attempts` tries (BT.CPP RetryUntilSuccessful).

    Child SUCCESS: SUCCESS, and the count starts again. Child RUNNING: RUNNING.
    `attempts=-1` retries for ever, as BT.CPP's `num_attempts="-1"`.
    Child FAILURE uses up one attempt; after the last one the decorator returns FAILURE.
    While attempts remain, what happens next follows BT.CPP 4: a child that failed at
    once (it was not RUNNING before this tick) is tried again on the next tick, and the
    decorator returns RUNNING meanwhile, so a retry loop never spins inside one tick; a
    child that failed after RUNNING is started again within the same tick.
    """

    __slots__ = ("_failures", "attempts")
    kind = "Retry"

    def __init__(self, child: Node | None = None, attempts: int = 1, name: str = "") -> None:
        if attempts < 1 and attempts != -1:
            raise ValueError(f"Retry needs at least one attempt (or -1), got {attempts}")
        super().__init__(child, name)
        self.attempts = attempts
        self._failures = 0

    def tick(self, world: World) -> Status:
        """Tick the child, retrying in this tick after a FAILURE that followed RUNNING, and
        answering RUNNING after an immediate FAILURE so the retry waits for the next tick.
        FAILURE once `attempts` failures are used up; the count then starts again."""
        child = self.children[0]
        while True:
            fresh = child.status is not RUNNING
            status = child.tick(world)
            if status is not FAILURE:
                if status is SUCCESS:
                    self._failures = 0
                break
            self._failures += 1
            if 0 < self.attempts <= self._failures:
                self._failures = 0
                break
            if fresh:
                status = RUNNING
                break
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Reset the failure count, so a halted Retry starts its next run with every attempt;
        then halt the child."""
        self._failures = 0
        super().halt(world)


class Timeout(Decorator):
    """Fails a child that is still RUNNING after `ticks` ticks, and halts it.

    BT.CPP counts milliseconds; btplan counts ticks so runs are reproducible. The count
    starts on the first tick that reaches the decorator while it is idle and ends
    when the child returns SUCCESS or FAILURE, or when the decorator is halted.
    """

    __slots__ = ("_used", "ticks")
    kind = "Timeout"

    def __init__(self, child: Node | None = None, ticks: int = 1, name: str = "") -> None:
        if ticks < 1:
            raise ValueError(f"Timeout needs at least one tick, got {ticks}")
        super().__init__(child, name)
        self.ticks = ticks
        self._used = 0

    def tick(self, world: World) -> Status:
        """Count this tick and tick the child; a child still RUNNING on the `ticks`-th tick is
        halted and the answer is FAILURE. A finished child resets the count."""
        self._used += 1
        child = self.children[0]
        status = child.tick(world)
        if status is RUNNING:
            if self._used >= self.ticks:
                child.halt(world)
                self._used = 0
                status = FAILURE
        else:
            self._used = 0
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Reset the count, so the next run gets all `ticks` again; then halt the child."""
        self._used = 0
        super().halt(world)


__all__ = ["Decorator", "ForceFailure", "ForceSuccess", "Inverter", "Retry", "Timeout"]
