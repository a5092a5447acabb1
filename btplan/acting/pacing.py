"""Ticking on a wall clock: a fixed rate, overruns counted, stop requests heard while waiting.

A robot's tree ticks at a rate (10 Hz is common): the loop never waits on a skill
(skills are polled, btplan.robot.contract), so a tick's own work is short, and the rest
of the period is spent here. A tick that takes longer than the period makes the next
one late; it starts at once, the schedule restarts from it (no burst of ticks to catch
up), and the overrun is counted.
"""

from __future__ import annotations

from collections.abc import Callable

from btplan.acting.clock import Clock, SystemClock

NAP = 0.05
"""Longest single sleep, so that a stop request is heard within it at a slow rate."""


class Stop(Exception):
    """Raised between ticks when the caller asks the run to stop."""


class Pacer:
    """Waits for each tick's time (`rate` ticks per second; none: no waiting)."""

    def __init__(self, rate: float | None, clock: Clock | None = None,
                 stop: Callable[[], bool] | None = None) -> None:
        self.period = 1.0 / rate if rate else 0.0
        self.clock = clock or SystemClock()
        self.stop = stop
        self.overruns = 0
        self.worst_lateness = 0.0
        self._next: float | None = None

    def wait(self) -> None:
        """Return when the next tick is due; raise Stop when the caller asks to stop."""
        if self.period:
            now = self.clock.now()
            if self._next is None:
                self._next = now
            late = now - self._next
            if late > 0:
                self.overruns += 1
                self.worst_lateness = max(self.worst_lateness, late)
                self._next = now
            while (delay := self._next - self.clock.now()) > 0:
                if self.stop is not None and self.stop():
                    raise Stop
                self.clock.sleep(min(delay, NAP))
            self._next += self.period
        if self.stop is not None and self.stop():
            raise Stop
