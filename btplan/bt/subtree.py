"""SubTree: a tree instance inside another, with its own blackboard (BT.CPP 4).

The child is the root of a fresh instance of the called tree; `board` is that
instance's blackboard, remapped to the caller's. The status passes through unchanged,
and halting the SubTree halts the instance.
"""

from __future__ import annotations

from btplan.bt.blackboard import Blackboard
from btplan.bt.decorators import Decorator
from btplan.bt.node import Node
from btplan.bt.status import RUNNING, SKIPPED, Status
from btplan.bt.world import World


class SubTree(Decorator):
    """Ticks the called tree's root and answers what it answers."""

    __slots__ = ("board", "tree_id")
    kind = "SubTree"

    def __init__(self, child: Node | None, tree_id: str, board: Blackboard, name: str = "") -> None:
        super().__init__(child, name)
        self.tree_id = tree_id
        self.board = board

    def tick(self, world: World) -> Status:
        """Tick the instance's root and pass its status on; a SKIPPED root is passed on too,
        with the SubTree itself marked RUNNING."""
        status = self.children[0].tick(world)
        self.status = RUNNING if status is SKIPPED else status
        return status


__all__ = ["SubTree"]
