"""The time a run is paced by: the system's monotonic clock, or one a test moves by hand.

A robot acts on a wall clock (`rate=10`: one tick every 100 ms); the loop asks the clock
for the time and sleeps on it, and nothing else in the loop reads the time of day, so a
test runs an hour of robot time in a millisecond with `FakeClock`.
"""

from __future__ import annotations

import time

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

__all__ = ["Clock", "FakeClock", "SystemClock"]


class Clock(Protocol):
    """Monotonic seconds, and a sleep that a stop request may cut short."""

    def now(self) -> float:
        """Seconds from an arbitrary start that never go back: only differences count."""
        ...

    def sleep(self, seconds: float) -> None:
        """Wait `seconds` (not at all for zero or less); a stop request may end it early."""
        ...


class SystemClock:
    """`time.monotonic` and `time.sleep`."""

    def now(self) -> float:
        """`time.monotonic`: a change of the time of day cannot stretch or shrink a tick."""
        return time.monotonic()

    def sleep(self, seconds: float) -> None:
        """`time.sleep`, skipped for a wait of zero or less (a tick that overran its period)."""
        if seconds > 0:
            time.sleep(seconds)


class FakeClock:
    """A clock that moves only when slept on or advanced: tests of pacing without waiting.
    `sleeps` lists every sleep asked for."""

    def __init__(self, start: float = 0.0) -> None:
        self.time = start
        self.sleeps: list[float] = []

    def now(self) -> float:
        """`start` plus every sleep and advance so far."""
        return self.time

    def sleep(self, seconds: float) -> None:
        """Note the sleep asked for and move time by it at once (never backwards), so no test
        waits."""
        self.sleeps.append(seconds)
        self.time += max(0.0, seconds)

    def advance(self, seconds: float) -> None:
        """Time passes (a tick that took `seconds`, a skill that ran)."""
        self.time += seconds
