"""BehaviorTree.CPP 4's pre- and post-condition attributes, on any node.

`_failureIf`, `_successIf`, `_skipIf` and `_while` are checked, in that order, before
a node that is not RUNNING is ticked: the first that applies decides the status
without ticking the node (`_while` false means SKIPPED). While the node is RUNNING only
`_while` is checked; when it turns false the node is halted and SKIPPED. After the
node finishes, `_onSuccess` or `_onFailure` runs, then `_post`; `_onHalted` runs when
a RUNNING node is halted. A node skipped this way keeps its previous status, as in
BT.CPP (which does not store SKIPPED).

A node with conditions gets its class switched to a guarded twin with the same slots
(the trick the tracer uses), so nodes without conditions pay nothing.
"""

from __future__ import annotations

from collections.abc import Callable

from btplan.bt.blackboard import Blackboard
from btplan.bt.node import Node, Origin
from btplan.bt.script import Script
from btplan.bt.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.world import World

PRE = ("_failureIf", "_successIf", "_skipIf", "_while")
POST = ("_onSuccess", "_onFailure", "_post", "_onHalted")


class Guard:
    """The compiled condition scripts of one node and the blackboard they read."""

    __slots__ = ("board", "scripts")

    def __init__(self, scripts: dict[str, Script], board: Blackboard) -> None:
        self.scripts = scripts
        self.board = board

    def before(self, running: bool) -> Status | None:
        """The status the conditions decide before a tick, or None to tick the node. A node not
        RUNNING goes through `_failureIf`, `_successIf`, `_skipIf`, then `_while` (false:
        SKIPPED); a RUNNING one through `_while` only."""
        scripts, board = self.scripts, self.board
        if running:
            loop = scripts.get("_while")
            return SKIPPED if loop is not None and not loop.holds(board) else None
        for name, answer in (("_failureIf", FAILURE), ("_successIf", SUCCESS),
                             ("_skipIf", SKIPPED)):
            script = scripts.get(name)
            if script is not None and script.holds(board):
                return answer
        loop = scripts.get("_while")
        return SKIPPED if loop is not None and not loop.holds(board) else None

    def after(self, status: Status) -> None:
        """Run `_onSuccess` or `_onFailure`, then `_post`, once the node has finished; nothing
        while it is RUNNING or when it was SKIPPED."""
        name = ("_onSuccess" if status is SUCCESS else "_onFailure" if status is FAILURE
                else None)
        if name is None:
            return
        if name in self.scripts:
            self.scripts[name].run(self.board)
        if "_post" in self.scripts:
            self.scripts["_post"].run(self.board)

    def halted(self) -> None:
        """Run `_onHalted`; the guarded halt calls it only for a node that was RUNNING."""
        if "_onHalted" in self.scripts:
            self.scripts["_onHalted"].run(self.board)


_GUARDED: dict[type[Node], type[Node]] = {}


def _guarded_class(cls: type[Node]) -> type[Node]:
    if cls in _GUARDED.values():
        return cls
    if cls in _GUARDED:
        return _GUARDED[cls]
    base_tick: Callable[[Node, World], Status] = cls.tick
    base_halt: Callable[[Node, World], None] = cls.halt

    def tick(self: Node, world: World) -> Status:
        guard: Guard = self.origin.guard  # type: ignore[union-attr, assignment]
        running = self.status is RUNNING
        decided = guard.before(running)
        if decided is None:
            status = base_tick(self, world)
        else:
            status = decided
            if decided is SKIPPED and running:
                halt(self, world)
            elif decided is not SKIPPED:
                self.status = decided
        guard.after(status)
        return status

    def halt(self: Node, world: World) -> None:
        was_running = self.status is RUNNING
        base_halt(self, world)
        if was_running:
            guard: Guard = self.origin.guard  # type: ignore[union-attr, assignment]
            guard.halted()

    twin = type(cls.__name__, (cls,), {"__slots__": (), "tick": tick, "halt": halt,
                                       "__doc__": cls.__doc__, "__module__": cls.__module__})
    _GUARDED[cls] = twin
    return twin


def guard(node: Node, scripts: dict[str, Script], board: Blackboard) -> None:
    """Attach condition scripts to a node read from XML (it must have an origin)."""
    if not scripts:
        return
    if node.origin is None:
        node.origin = Origin(node.kind, ())
    node.origin.guard = Guard(scripts, board)
    node.__class__ = _guarded_class(type(node))


__all__ = ["POST", "PRE", "Guard", "guard"]
