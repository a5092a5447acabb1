"""Condition and Action leaves: the only nodes that talk to the world.

A leaf is one grounded predicate or action: `ident` is the predicate or action
template name (`holding`, `Pick`), `args` the grounded arguments and `ports` the
parameter names they bind, which is what the XML export writes as port attributes.
"""

from __future__ import annotations

from btplan.bt.node import Node
from btplan.bt.status import FAILURE, IDLE, RUNNING, SUCCESS, Status
from btplan.bt.world import LeafKey, World


def leaf_label(ident: str, args: tuple[str, ...]) -> str:
    """`holding(cube)`, or just `hand_empty` without arguments, as the paper writes them."""
    return f"{ident}({', '.join(args)})" if args else ident


class Leaf(Node):
    """A condition or an action: one ID (a predicate, an action template) and the
    grounded arguments, named by ports; `key` is what the world is asked about."""

    __slots__ = ("args", "ident", "key", "ports")
    kind = "Leaf"

    def __init__(
        self,
        ident: str,
        args: tuple[str, ...] = (),
        ports: tuple[str, ...] | None = None,
        name: str = "",
    ) -> None:
        # Node.__init__ and leaf_label written out (tests/bt/test_nodes.py checks both):
        # planning builds a hundred leaves a run, and the calls cost as much as the rest
        self.name = name or (f"{ident}({', '.join(args)})" if args else ident)
        self.status = IDLE
        self.parent = None
        self.origin = None
        self.ident = ident
        self.args = args = tuple(args)
        self.ports = ports = (tuple(ports) if ports is not None
                              else tuple(f"arg{i}" for i in range(len(args))))
        if len(ports) != len(args):
            raise ValueError(f"{self.name}: {len(ports)} port names for {len(args)} arguments")
        self.key: LeafKey = (ident, args)


class Condition(Leaf):
    """SUCCESS when the world says the condition holds, FAILURE otherwise; never RUNNING."""

    __slots__ = ()
    kind = "Condition"

    def tick(self, world: World) -> Status:
        """Ask the world whether the condition holds."""
        self.status = status = SUCCESS if world.check(self.key) else FAILURE
        return status


class Action(Leaf):
    """Starts the grounded action on the first tick that reaches it, then steps it.

    Returns what the world returns. When halted while RUNNING, the world is told, so a
    controller can stop the robot; the next tick that reaches it starts it afresh.
    """

    __slots__ = ()
    kind = "Action"

    def tick(self, world: World) -> Status:
        """Start the action, or step it when it is running; the world's answer."""
        if self.status is RUNNING:
            status = world.step(self.key)
        else:
            status = world.start(self.key)
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Tell the world to stop the action, if it is running."""
        if self.status is RUNNING:
            world.halt(self.key)
        self.status = IDLE
