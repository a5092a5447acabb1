"""BehaviorTree.CPP 4's built-in leaves: they work on the blackboard, not on the world.

AlwaysSuccess/AlwaysFailure, Sleep, SetBlackboard, UnsetBlackboard, Script,
ScriptCondition and WasEntryUpdated. They never call the world, so an imported tree
whose only leaves are these ticks the same with any world. Sleep counts ticks like
btplan's Timeout.
"""

from __future__ import annotations

from btplan.bt.blackboard import NodeError, Ports, as_text, pointer
from btplan.bt.node import Node
from btplan.bt.script import Script
from btplan.bt.status import FAILURE, IDLE, RUNNING, SUCCESS, Status
from btplan.bt.world import World


class Constant(Node):
    """AlwaysSuccess (`result=SUCCESS`) or AlwaysFailure (`result=FAILURE`)."""

    __slots__ = ("result",)
    kind = "Constant"

    def __init__(self, result: Status, name: str = "") -> None:
        super().__init__(name)
        self.result = result

    def tick(self, world: World) -> Status:
        """Answer the fixed `result`, without asking the world or reading the blackboard."""
        self.status = status = self.result
        return status


class Sleep(Node):
    """RUNNING for `ticks` ticks, then SUCCESS; SUCCESS at once for zero ticks."""

    __slots__ = ("_left", "ticks")
    kind = "Sleep"

    def __init__(self, ticks: int, name: str = "") -> None:
        super().__init__(name)
        self.ticks = ticks
        self._left = 0

    def tick(self, world: World) -> Status:
        """A tick that finds it idle arms the countdown: RUNNING on that tick and the next
        `ticks - 1`, SUCCESS on the one after. A halt rearms it for the next run."""
        if self.status is not RUNNING:
            self._left = self.ticks
            if self._left <= 0:
                self.status = SUCCESS
                return SUCCESS
        elif self._left <= 0:
            self.status = SUCCESS
            return SUCCESS
        self._left -= 1
        self.status = RUNNING
        return RUNNING


class SetBlackboard(Node):
    """Writes `value` to the entry named by `output_key`; SUCCESS.

    A `{key}` value copies that entry (an error if it does not exist); anything else
    is stored as text, as BT.CPP stores it.
    """

    __slots__ = ("ports",)
    kind = "SetBlackboard"

    def __init__(self, ports: Ports, name: str = "") -> None:
        super().__init__(name)
        self.ports = ports

    def tick(self, world: World) -> Status:
        """Copy the `{key}` entry or store the literal text, then SUCCESS. A missing `value`,
        an unset source entry or an unresolvable `output_key` raises NodeError, as BT.CPP
        throws there instead of failing."""
        board = self.ports.board
        raw = self.ports.values.get("value")
        if raw is None:
            raise NodeError(f"{self.ports.owner}: input port 'value' is not set")
        source = pointer(raw, "value")
        if source is not None:
            if not board.has(source):
                raise NodeError(f"{self.ports.owner}: value reads {{{source}}}, which is not set")
            value = board.get(source)
        else:
            value = raw
        board.set(self._output_key(), value)
        self.status = SUCCESS
        return SUCCESS


    def _output_key(self) -> str:
        """BT.CPP reads `output_key` as an input: a bare name is the key, and `{x}` means
        the key is the text stored in entry x (an error when x is not set)."""
        raw = self.ports.values.get("output_key")
        if raw is None:
            raise NodeError(f"{self.ports.owner}: missing port 'output_key'")
        source = pointer(raw, "output_key")
        if source is None:
            return raw
        if not self.ports.board.has(source):
            raise NodeError(f"{self.ports.owner}: missing port 'output_key' ({{{source}}} "
                            "is not set)")
        return as_text(self.ports.board.get(source))


class UnsetBlackboard(Node):
    """Removes the entry named by `key`; SUCCESS (also when there was none)."""

    __slots__ = ("ports",)
    kind = "UnsetBlackboard"

    def __init__(self, ports: Ports, name: str = "") -> None:
        super().__init__(name)
        self.ports = ports

    def tick(self, world: World) -> Status:
        """Remove the entry `key` names, SUCCESS whether or not it existed; only a missing
        `key` port raises NodeError."""
        self.ports.board.unset(self.ports.key("key"))
        self.status = SUCCESS
        return SUCCESS


class ScriptAction(Node):
    """BT.CPP Script: runs `code` against the blackboard; SUCCESS."""

    __slots__ = ("ports", "script")
    kind = "Script"

    def __init__(self, script: Script, ports: Ports, name: str = "") -> None:
        super().__init__(name)
        self.script = script
        self.ports = ports

    def tick(self, world: World) -> Status:
        """Run the script for its effect on the blackboard; always SUCCESS. A script that cannot
        run (an unset entry, strings in arithmetic) raises NodeError rather than failing."""
        self.script.run(self.ports.board)
        self.status = SUCCESS
        return SUCCESS


class ScriptCondition(Node):
    """BT.CPP ScriptCondition: SUCCESS when `code` evaluates true, else FAILURE."""

    __slots__ = ("ports", "script")
    kind = "ScriptCondition"

    def __init__(self, script: Script, ports: Ports, name: str = "") -> None:
        super().__init__(name)
        self.script = script
        self.ports = ports

    def tick(self, world: World) -> Status:
        """SUCCESS when the script's last value reads as true (non-zero, `true`), FAILURE
        otherwise; never RUNNING. Assignments in the script do take effect."""
        self.status = status = SUCCESS if self.script.holds(self.ports.board) else FAILURE
        return status


class WasEntryUpdated(Node):
    """SUCCESS if `entry` was written since this node last looked, else FAILURE."""

    __slots__ = ("_seen", "ports")
    kind = "WasEntryUpdated"

    def __init__(self, ports: Ports, name: str = "") -> None:
        super().__init__(name)
        self.ports = ports
        self._seen = 0

    def tick(self, world: World) -> Status:
        """Compare the entry's write count with the one seen on the previous tick: the first
        tick counts any earlier write as new, and an entry never written is FAILURE."""
        seq = self.ports.board.sequence(self.ports.key("entry"))
        updated, self._seen = seq != self._seen, seq
        self.status = status = SUCCESS if updated else FAILURE
        return status

    def halt(self, world: World) -> None:
        """Reset only the status: the write count seen is kept, so a halt does not make an old
        write look new on the next tick."""
        self.status = IDLE


__all__ = ["Constant", "ScriptAction", "ScriptCondition", "SetBlackboard", "Sleep",
           "UnsetBlackboard", "WasEntryUpdated"]
