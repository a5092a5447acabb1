"""The small protocol through which leaves reach a world (symbolic, PyBullet, a test stub).

The tree knows nothing of planning or of any backend: a leaf only carries a key,
`(name, args)`, e.g. `("holding", ("cube",))` or `("Pick", ("cube",))`, and hands it
to the world. The same tree therefore runs on every backend.
"""

from __future__ import annotations

from btplan.bt.status import Status

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

LeafKey = tuple[str, tuple[str, ...]]


class World(Protocol):
    """What a world must answer for the tree to tick against it."""

    def check(self, key: LeafKey) -> bool:
        """Whether the grounded condition holds now; never blocks, never RUNNING."""
        ...

    def start(self, key: LeafKey) -> Status:
        """Begin a grounded action; RUNNING while it takes more ticks."""
        ...

    def step(self, key: LeafKey) -> Status:
        """Advance an action that returned RUNNING on the previous tick it was reached."""
        ...

    def halt(self, key: LeafKey) -> None:
        """Stop a RUNNING action that the tree no longer reaches."""
        ...
