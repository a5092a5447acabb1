"""A tree with a root, a tick counter and the root-level tick."""

from __future__ import annotations

from btplan.bt.node import Node
from btplan.bt.status import Status
from btplan.bt.world import World


class BehaviorTree:
    """Owns the root so the planner can replace it (Algorithm 1 grows the tree at the root)."""

    __slots__ = ("root", "ticks", "name")

    def __init__(self, root: Node, name: str = "Main") -> None:
        self.root = root
        self.ticks = 0
        self.name = name

    def tick(self, world: World) -> Status:
        self.ticks += 1
        return self.root.tick(world)

    def halt(self, world: World) -> None:
        self.root.halt(world)

    def nodes(self) -> list[Node]:
        return self.root.walk()
