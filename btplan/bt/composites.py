"""Sequence and Fallback, reactive (the paper's semantics) or with memory (BT.CPP's).

Reactive (memory=False, the default; BT.CPP ReactiveSequence/ReactiveFallback):
every tick starts again at the first child.
  Sequence: a child's SUCCESS ticks the next child; FAILURE or RUNNING is returned at
  once. Fallback: a child's FAILURE ticks the next child; SUCCESS or RUNNING is returned
  at once. In both, a child that was RUNNING on an earlier tick and is not the child that
  decided this tick's outcome is halted, so that an action the tree no longer reaches
  learns it was stopped (the cube slipping out of the gripper halts MoveTo). Only the
  children right of the deciding one can be in that state: every child left of it was
  ticked on this tick and has already finished.

A child that answers SKIPPED (BT.CPP 4's `_skipIf`) is passed over. The variants in
`btcpp_composites.py` that trees read from BT.CPP XML use also answer SKIPPED when all
children were skipped; these stay free of that count.

The memoryless loops ask the world in place for a plain `Condition` child, doing what
its `tick` does (status from `world.check`), because a Python call per leaf was a large
share of a reactive tick; Sequence does the same for a plain `Action` (`world.start`,
or `world.step` when RUNNING), the last child of every PA-BT Sequence, and both halt
such leaves in place. Only the exact classes are treated so: a subclass (a custom
leaf, a traced or guarded twin) goes through its own `tick` and `halt`.

With memory (memory=True; BT.CPP Sequence/Fallback): a RUNNING child is resumed on the
next tick without re-ticking the children before it. The index is reset when the
node returns SUCCESS or FAILURE, and when it is halted.
"""

from __future__ import annotations

import types

from btplan.bt.leaves import Action, Condition
from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, IDLE, RUNNING, SUCCESS, Status
from btplan.bt.world import World

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Callable
    from typing import Any


class _Control(Composite):
    """Shared state and the memory loop; `stop_on` is the child status that ends the loop
    early. The memoryless loop, which every tree the planner builds ticks, is written out
    in Sequence and Fallback (see `Sequence.tick`)."""

    __slots__ = ("_current", "memory")
    stop_on: Status = FAILURE

    def __init__(self, children: list[Node] | None = None, name: str = "", memory: bool = False):
        Composite.__init__(self, children, name)  # no super(): one object fewer per node
        self.memory = memory
        self._current = 0

    def tick(self, world: World) -> Status:
        """The loop with memory: resume at the child that was RUNNING."""
        children = self.children
        start = self._current if self.memory else 0
        stop_on = self.stop_on
        for i in range(start, len(children)):
            status = children[i].tick(world)
            if status is RUNNING or status is stop_on:
                if i + 1 < len(children):  # the last child has nothing right of it
                    self._halt_after(i, world)
                self._current = i if status is RUNNING else 0
                self.status = status
                return status
        self._current = 0
        self.status = status = SUCCESS if stop_on is FAILURE else FAILURE
        return status

    def _halt_after(self, index: int, world: World) -> None:
        """Halt the children right of the deciding one that are still active."""
        children = self.children
        for j in range(index + 1, len(children)):
            if children[j].status is not IDLE:
                children[j].halt(world)

    def halt(self, world: World) -> None:
        """Rewind, then halt every child that is not idle (Composite.halt written out: a
        reactive tree halts a preempted subtree node by node). A plain Condition or Action
        child is halted in place, as its own `halt` would: most nodes of a preempted
        subtree are leaves. The child's class is tested before its status is read, so
        that each status read or write below sees one class (see `_own_copy`)."""
        self._current = 0
        for child in self.children:
            if type(child) is Condition:
                child.status = IDLE
            elif type(child) is Action:
                if child.status is RUNNING:
                    world.halt(child.key)
                child.status = IDLE
            elif child.status is not IDLE:
                child.halt(world)
        self.status = IDLE


def _own_copy(method: Callable[[_Control, World], None]) -> Any:
    """`method` with a code object of its own, for one subclass.

    CPython (3.11 on) specialises each attribute read and write of a function's code
    for the one class it keeps meeting there, and falls back to a slower generic lookup
    where classes alternate. `_Control.halt`, shared by Sequence and Fallback, met both
    (and both as children); with a copy each, every such access in a PA-BT tree sees
    one class.
    """
    assert isinstance(method, types.FunctionType)
    copy = types.FunctionType(method.__code__.replace(), method.__globals__,
                              method.__name__, method.__defaults__, method.__closure__)
    copy.__doc__, copy.__qualname__ = method.__doc__, method.__qualname__
    copy.__annotations__ = method.__annotations__
    return copy


class Sequence(_Control):
    """Ticks children left to right while they succeed (the paper's "->").

    Child SUCCESS: tick the next child (SUCCESS after the last). Child FAILURE or
    RUNNING: return it, and halt the children to its right.
    """

    __slots__ = ()
    kind = "Sequence"
    stop_on = FAILURE
    halt = _own_copy(_Control.halt)

    def tick(self, world: World) -> Status:
        """Memoryless: every child from the first, until one fails or runs (see the class).

        The loop is the engine's hottest code, so it keeps to what a reactive tick needs:
        no index (the deciding child is found again only when more than one child follows
        it), no rewind counter, constants rather than `stop_on`.
        """
        if self.memory:
            return _Control.tick(self, world)
        children = self.children
        for child in children:
            if type(child) is Condition:  # asked in place, see the module
                if world.check(child.key):
                    child.status = SUCCESS
                    continue
                child.status = status = FAILURE
            else:
                if type(child) is Action:  # in place too: a PA-BT Sequence ends with its action
                    status = child.status = (world.step(child.key) if child.status is RUNNING
                                             else world.start(child.key))
                else:
                    status = child.tick(world)
                if status is SUCCESS or status is not FAILURE and status is not RUNNING:
                    continue
            last = children[-1]
            if child is not last:
                if children[-2] is child:  # a precondition before the action
                    if last.status is not IDLE:
                        last.halt(world)
                else:
                    for other in children[children.index(child) + 1:]:
                        if other.status is not IDLE:
                            other.halt(world)
            self.status = status
            return status
        self.status = SUCCESS
        return SUCCESS


class Fallback(_Control):
    """Ticks children left to right while they fail (the paper's "?").

    Child FAILURE: tick the next child (FAILURE after the last). Child SUCCESS or
    RUNNING: return it, and halt the children to its right.
    """

    __slots__ = ()
    kind = "Fallback"
    stop_on = SUCCESS
    halt = _own_copy(_Control.halt)

    def tick(self, world: World) -> Status:
        """Memoryless: every child from the first, until one succeeds or runs (see the class
        and `Sequence.tick`)."""
        if self.memory:
            return _Control.tick(self, world)
        children = self.children
        for child in children:
            if type(child) is Condition:  # asked in place, see the module
                if not world.check(child.key):
                    child.status = FAILURE
                    continue
                child.status = status = SUCCESS
            else:
                status = child.tick(world)
                if status is not SUCCESS and status is not RUNNING:
                    continue
            last = children[-1]
            if child is not last:
                if children[-2] is child:  # the condition before the Sequence
                    if last.status is not IDLE:
                        last.halt(world)
                else:
                    for other in children[children.index(child) + 1:]:
                        if other.status is not IDLE:
                            other.halt(world)
            self.status = status
            return status
        self.status = FAILURE
        return FAILURE
