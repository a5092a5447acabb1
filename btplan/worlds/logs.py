"""The recent part of a world's action logs: a list that keeps its last entries only.

The symbolic and simulated worlds log the actions they started, halted and saw fail,
for their agents and for tests; a run that goes on for a million ticks must not keep
a million entries. The acting loop keeps its own counts (btplan.acting.skills).
"""

from __future__ import annotations

KEPT = 10_000
"""Entries a log keeps; older ones are dropped, a thousand at a time."""

TYPE_CHECKING = False
if TYPE_CHECKING:  # `typing` is left unimported to run: `btplan plan` starts without it
    from typing import TypeVar

    T = TypeVar("T")

    class RecentLog(list[T]):
        """A list whose `append` drops the oldest entries once it holds more than KEPT."""

        def append(self, item: T) -> None: ...
else:
    class RecentLog(list):
        """A list whose `append` drops the oldest entries once it holds more than KEPT."""

        def append(self, item):
            super().append(item)
            if len(self) > KEPT + 1000:
                del self[:1000]
