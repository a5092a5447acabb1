"""A memory limit that stops the work with a message, before the OOM killer ends it.

`--max-memory SIZE` caps the process's data (heap and anonymous mappings, Linux's
RLIMIT_DATA): an allocation past it raises MemoryError in the planner, which the command
turns into exit 1 naming the limit, instead of the kernel killing the process (and, on
a robot's computer, maybe something else). The default is 80% of the machine's memory.
"""

from __future__ import annotations

import os
from types import TracebackType

from btplan.errors import InputError, Span

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Self

DEFAULT_SHARE = 0.8
"""Of the machine's memory, what the default limit allows."""

UNITS = {"": 1, "K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40}


def parse_memory(text: str) -> int | None:
    """Bytes from `2G`, `500M`, `1048576`; None for `0` (no limit); `auto` for the default."""
    value = text.strip().upper().removesuffix("B").removesuffix("I")
    if value == "AUTO":
        return machine_default()
    unit = value[-1:] if value[-1:] in UNITS and value[-1:] else ""
    number = value[:-1] if unit else value
    try:
        size = float(number) * UNITS[unit]
    except ValueError:
        raise InputError(f"expected a size such as 2G, 500M or 0 (no limit), not {text!r}",
                         Span("--max-memory", 1, 1)) from None
    if size < 0:
        raise InputError("a memory limit cannot be negative", Span("--max-memory", 1, 1))
    return None if size == 0 else int(size)


def machine_default() -> int | None:
    """80% of the machine's memory, or None where it cannot be told."""
    try:
        return int(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") * DEFAULT_SHARE)
    except (ValueError, OSError, AttributeError):
        return None


def describe(size: int) -> str:
    """`1.5 GB`, `300 MB`: a size as the messages say it."""
    return f"{size / 2**30:.1f} GB" if size >= 2**30 else f"{size / 2**20:.0f} MB"


class MemoryLimit:
    """While active, the process's data may not grow past `size` bytes (None: no limit)."""

    def __init__(self, size: int | None) -> None:
        self.size = size
        self._previous: tuple[int, int] | None = None

    def __enter__(self) -> Self:
        if self.size is None:
            return self
        try:
            import resource
        except ImportError:  # not a POSIX system: no limit to set
            return self
        soft, hard = resource.getrlimit(resource.RLIMIT_DATA)
        wanted = self.size if hard == resource.RLIM_INFINITY else min(self.size, hard)
        self._previous = (soft, hard)
        resource.setrlimit(resource.RLIMIT_DATA, (wanted, hard))
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._previous is not None:
            import resource

            resource.setrlimit(resource.RLIMIT_DATA, self._previous)
            self._previous = None
