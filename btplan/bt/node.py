"""The base of every tree node: a name, a last status, a parent link, tick and halt."""

from __future__ import annotations

from btplan.bt.status import IDLE, Status
from btplan.bt.world import World

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import ClassVar


class Origin:
    """Where a node read from BT.CPP XML came from: its tag and attributes as written.

    The XML export writes them back unchanged, so an imported tree leaves btplan node
    for node; `guard` holds its compiled pre/post-condition scripts, if any. The tick
    never reads this: plain nodes cost nothing for it.
    """

    __slots__ = ("attrs", "guard", "tag")

    def __init__(self, tag: str, attrs: tuple[tuple[str, str], ...], guard: object = None
                 ) -> None:
        self.tag = tag
        self.attrs = attrs
        self.guard = guard


class Node:
    """A node of a Behavior Tree.

    `status` is the status of the last tick that reached the node (IDLE before the
    first one and after a halt). `parent` is kept so the planner can move subtrees
    (IncreasePriority) without searching the whole tree.
    """

    __slots__ = ("name", "origin", "parent", "status")
    kind: ClassVar[str] = "Node"

    def __init__(self, name: str = "") -> None:
        self.name = name
        self.status: Status = IDLE
        self.parent: Composite | None = None
        self.origin: Origin | None = None

    @property
    def children(self) -> list[Node]:
        """The node's children, in order (none for a leaf)."""
        return []

    def tick(self, world: World) -> Status:
        """Tick the node once against `world`: SUCCESS, FAILURE or RUNNING."""
        raise NotImplementedError

    def halt(self, world: World) -> None:
        """Stop whatever this node has RUNNING; a no-op on a node that is not running."""
        self.status = IDLE

    def walk(self) -> list[Node]:
        """This node and all below it, depth first, left to right."""
        out: list[Node] = []
        stack: list[Node] = [self]
        while stack:
            node = stack.pop()
            out.append(node)
            stack.extend(reversed(node.children))
        return out


class Composite(Node):
    """A control node with an ordered list of children.

    `children` is a plain slot here, over Node's property: the planner reads it thousands
    of times a run, and a property costs a Python call per read. Change it through
    `insert` and `remove`, which keep the parent links."""

    __slots__ = ("children",)
    kind: ClassVar[str] = "Composite"

    def __init__(self, children: list[Node] | None = None, name: str = "") -> None:
        # Node.__init__ written out (tests/bt/test_nodes.py checks every field is set):
        # planning builds composites by the dozen a run, and the call cost as much as
        # the fields it sets
        self.name = name
        self.status = IDLE
        self.parent = None
        self.origin = None
        self.children: list[Node] = []
        if children and type(self).insert is Composite.insert:  # `append` each, inlined
            for child in children:
                if child.parent is not None:
                    raise ValueError(f"node {child.name!r} already has a parent")
                child.parent = self
                self.children.append(child)
            return
        for child in children or []:
            self.append(child)

    def append(self, child: Node) -> None:
        """Add `child` as the last child."""
        self.insert(len(self.children), child)

    def insert(self, index: int, child: Node) -> None:
        """Add `child` at `index`; a node has one parent at most."""
        if child.parent is not None:
            raise ValueError(f"node {child.name!r} already has a parent")
        child.parent = self
        self.children.insert(index, child)

    def remove(self, child: Node) -> int:
        """Detach `child` and return the index it had."""
        index = self.index_of(child)
        del self.children[index]
        child.parent = None
        return index

    def replace(self, old: Node, new: Node) -> None:
        """Put `new` where `old` was; the planner's Substitute (Algorithm 2, line 10)."""
        index = self.remove(old)
        self.insert(index, new)

    def index_of(self, child: Node) -> int:
        """Where `child` is among the children (by identity)."""
        try:  # nodes compare by identity: the list finds it in C
            return self.children.index(child)
        except ValueError:
            raise ValueError(f"{child.name!r} is not a child of {self.name!r}") from None

    def halt(self, world: World) -> None:
        """Halt every child that is not idle, then this node."""
        for child in self.children:
            if child.status is not IDLE:
                child.halt(world)
        self.status = IDLE
