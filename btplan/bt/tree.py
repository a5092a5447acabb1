"""A tree with a root, a tick counter and the root-level tick."""

from __future__ import annotations

from btplan.bt.node import Node
from btplan.bt.status import Status
from btplan.bt.world import World

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

if TYPE_CHECKING:
    from btplan.bt.formats.btcpp_files import ImportedTrees

class TickRecorder(Protocol):
    """What the tree needs of a recorder (`btplan.bt.trace.TickRecorder` is one).

    A protocol rather than an import, so that trace.py may import this module without
    closing an import circle.
    """

    def tick(self, tree: BehaviorTree, world: World) -> Status:
        """Tick `tree` against `world` and record what the tick reached."""
        ...


class BehaviorTree:
    """Owns the root so the planner can replace it (Algorithm 1 grows the tree at the root).

    With `debug=True` every tick goes through `StrictWorld`, which raises when a
    condition answers RUNNING or an action answers something that is not a status.
    With a `recorder` (see `btplan.bt.trace.TickRecorder`), every tick is recorded;
    without one, ticking costs nothing extra. `imported` holds what a tree read from
    BT.CPP XML needs to be written back node for node (its other trees, its models).
    """

    __slots__ = ("debug", "imported", "name", "recorder", "root", "ticks")

    def __init__(self, root: Node, name: str = "Main", debug: bool = False) -> None:
        self.root = root
        self.ticks = 0
        self.name = name
        self.debug = debug
        self.recorder: TickRecorder | None = None
        self.imported: ImportedTrees | None = None

    def tick(self, world: World) -> Status:
        """Tick the root once against `world` (through the recorder when one is attached)."""
        self.ticks += 1
        if self.debug:
            from btplan.bt.debug import StrictWorld  # only with --debug

            world = StrictWorld(world)
        if self.recorder is not None:
            return self.recorder.tick(self, world)
        return self.root.tick(world)

    def halt(self, world: World) -> None:
        """Halt everything the tree has RUNNING (the world is told of each action)."""
        self.root.halt(world)

    def narrow_to(self, part: Node, world: World) -> None:
        """Make `part`, a subtree, the root: it is detached with its nodes' statuses (an
        action it runs goes on), and what lay around it is halted and dropped."""
        root = self.root
        if part is root:
            return
        if part.parent is not None:
            part.parent.remove(part)
        root.halt(world)
        self.root = part

    def nodes(self) -> list[Node]:
        """Every node, depth first, left to right."""
        return self.root.walk()
