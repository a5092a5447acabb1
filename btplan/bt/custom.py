"""Custom nodes of an imported tree: leaves whose ports read the blackboard, and
controls or decorators whose code only exists in C++.

A custom leaf is still a btplan Condition or Action that asks the world; when one of
its ports is `{key}`, the argument handed to the world is the entry's value at tick
time (or the literal text while the entry does not exist), so a world can answer
`Pick(target)` after a Script set `target`. A custom control or decorator has no
semantics btplan could know: the tree can be viewed and converted, and ticking it is
an error that names the node.
"""

from __future__ import annotations

from btplan.bt.blackboard import Blackboard, NodeError, as_text, pointer
from btplan.bt.leaves import Action, Condition
from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, IDLE, RUNNING, SUCCESS, Status
from btplan.bt.world import LeafKey, World


def _resolve(ident: str, args: tuple[str, ...], ports: tuple[str, ...],
             board: Blackboard) -> LeafKey:
    values = []
    for port, raw in zip(ports, args, strict=True):
        key = pointer(raw, port)
        values.append(as_text(board.get(key)) if key is not None and board.has(key) else raw)
    return ident, tuple(values)


class BoundCondition(Condition):
    """A custom condition with `{key}` ports, resolved on every tick."""

    __slots__ = ("board",)

    def __init__(self, ident: str, args: tuple[str, ...], ports: tuple[str, ...],
                 board: Blackboard, name: str = "") -> None:
        super().__init__(ident, args, ports, name)
        self.board = board

    def tick(self, world: World) -> Status:
        """Ask the world with each `{key}` port replaced by its entry's current text (the
        literal while the entry is unset), so a Script can choose the argument; never RUNNING."""
        key = _resolve(self.ident, self.args, self.ports, self.board)
        self.status = status = SUCCESS if world.check(key) else FAILURE
        return status


class BoundAction(Action):
    """A custom action with `{key}` ports; the key is fixed when the action starts, so
    `step` and `halt` reach the same running action."""

    __slots__ = ("board", "running_key")

    def __init__(self, ident: str, args: tuple[str, ...], ports: tuple[str, ...],
                 board: Blackboard, name: str = "") -> None:
        super().__init__(ident, args, ports, name)
        self.board = board
        self.running_key = self.key

    def tick(self, world: World) -> Status:
        """Resolve the `{key}` ports only when the action starts and keep that key while it
        runs, so an entry changed mid-action does not make `step` ask about another action."""
        if self.status is RUNNING:
            status = world.step(self.running_key)
        else:
            self.running_key = _resolve(self.ident, self.args, self.ports, self.board)
            status = world.start(self.running_key)
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Halt the action the world actually started (`running_key`), not the one the entries
        would name now."""
        if self.status is RUNNING:
            world.halt(self.running_key)
        self.status = IDLE


class Opaque(Composite):
    """A custom control (`kind` Control) or decorator whose behaviour lives in C++."""

    __slots__ = ("ident", "node_kind")
    kind = "Custom"

    def __init__(self, ident: str, node_kind: str, children: list[Node] | None = None,
                 name: str = "") -> None:
        super().__init__(children, name)
        self.ident = ident
        self.node_kind = node_kind

    def tick(self, world: World) -> Status:
        """Always raise NodeError naming the node: its C++ behaviour is unknown, and guessing
        would make the tree tick unlike it does in BT.CPP."""
        raise NodeError(f"{self.ident} is a custom {self.node_kind.lower()} whose behaviour "
                        "btplan cannot know; it can be viewed and converted, not ticked")


__all__ = ["BoundAction", "BoundCondition", "Opaque"]
