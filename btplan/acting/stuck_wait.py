"""A run on a wall clock gives a dead end a moment to pass before it counts as stuck.

A robot's facts come from sensors read at different moments: a service answered now,
a topic last heard a few milliseconds ago. An action's effects then show in halves:
the hand reads empty no more while the object is not yet read as held. For that
moment the state has no way forward (nothing empties the hand of nothing), the tree
fails, and the loop finds nothing to expand. On a clock the next reading, one tick
later, has both halves, and the tree goes on as planned. So a paced run keeps ticking
for up to `ActingConfig.stuck_wait` seconds after the loop first found itself stuck;
the run ends as stuck (or plans offline, btplan.acting.offline_turns) only if the tree
still fails when that time is up. A tick that does not fail ends the wait.

A run without a rate has no clock to wait on (a symbolic world changes only when the
loop or its agents act), so it ends at once, as Algorithm 1 does.
"""

from __future__ import annotations

from btplan.acting.clock import Clock
from btplan.bt import FAILURE, Status
from btplan.errors import PlanningError

__all__ = ["StuckWait"]


class StuckWait:
    """When the loop first got stuck in a paced run, and the error it got stuck with."""

    def __init__(self, seconds: float, clock: Clock | None) -> None:
        self.seconds = seconds if clock is not None else 0.0
        self.clock = clock
        self.since: float | None = None
        """Clock time of the first stuck tick of the current wait; None: not waiting."""
        self.error: PlanningError | None = None
        """What the loop got stuck with, raised again if the wait ends with the tree failing."""

    def holds(self, error: PlanningError) -> bool:
        """Whether the run goes on ticking instead of ending on `error`: a wait starts,
        or the one under way has time left."""
        if not self.seconds or self.clock is None:
            return False
        now = self.clock.now()
        if self.since is None:
            self.since, self.error = now, error
        if now - self.since < self.seconds:
            return True
        self.since = self.error = None  # over: what the run does next starts afresh
        return False

    def after(self, status: Status) -> None:
        """A tick during the wait ended with `status`: the wait ends when the tree no
        longer fails; the stuck error comes back once the time is up and it still does."""
        if self.since is None:
            return
        if status is not FAILURE:
            self.since = self.error = None
            return
        assert self.clock is not None and self.error is not None
        if self.clock.now() - self.since >= self.seconds:
            raise self.error
