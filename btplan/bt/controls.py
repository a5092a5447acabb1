"""The other control nodes of BehaviorTree.CPP 4, with its tick semantics.

Sequence and Fallback (reactive or with memory) and Parallel live in their own
modules; these come into play when a tree is read from BT.CPP XML. "Fresh" below means
the child was not RUNNING before this tick, which is how BT.CPP tells a synchronous
child (it answers RUNNING to give other work a turn) from an asynchronous one.
"""

from __future__ import annotations

from btplan.bt.blackboard import NodeError, Ports, to_number
from btplan.bt.btcpp_composites import reset_children as _reset
from btplan.bt.composites import Fallback, Sequence
from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.world import World


class SequenceWithMemory(Sequence):
    """BT.CPP SequenceWithMemory: like a memory Sequence, but a FAILURE does not rewind.

    Child SUCCESS or SKIPPED: next child, except that after a fresh child's SUCCESS
    it yields (RUNNING) until the next tick, as BT.CPP 4.8 does. RUNNING: return it;
    the next tick resumes this child. FAILURE: return it, halting the children from it
    on, and keep the index, so the next tick starts again at the child that failed.
    Halting it does not rewind it either.
    """

    __slots__ = ()
    kind = "SequenceWithMemory"

    def __init__(self, children: list[Node] | None = None, name: str = "") -> None:
        super().__init__(children, name, memory=True)

    def tick(self, world: World) -> Status:
        """Resume at the child where the last tick stopped (running or failed); see the class
        for each child status. SKIPPED when every child was skipped; finishing resets all."""
        children = self.children
        skipped = True
        while self._current < len(children):
            fresh = children[self._current].status is not RUNNING
            status = children[self._current].tick(world)
            if status is RUNNING:
                self.status = RUNNING
                return RUNNING
            if status is FAILURE:
                self._halt_after(self._current, world)
                self.status = FAILURE
                return FAILURE
            skipped = skipped and status is SKIPPED
            self._current += 1
            if status is SUCCESS and fresh and self._current < len(children):
                self.status = RUNNING  # BT.CPP yields after a synchronous child
                return RUNNING
        self._current = 0
        _reset(self, world)
        self.status = RUNNING if skipped else SUCCESS
        return SKIPPED if skipped else SUCCESS

    def halt(self, world: World) -> None:
        """Halting does not rewind, as in BT.CPP 4: the next tick resumes at the child
        that was running or that failed."""
        Composite.halt(self, world)


class _Async:
    """AsyncSequence / AsyncFallback: a memory composite that returns RUNNING after a
    fresh child moves it on, so one tick never runs more than one synchronous child."""

    @staticmethod
    def run(node: Sequence | Fallback, world: World, moves_on: Status) -> Status:
        children = node.children
        while node._current < len(children):
            child = children[node._current]
            fresh = child.status is not RUNNING
            status = child.tick(world)
            if status is RUNNING:
                node.status = RUNNING
                return RUNNING
            if status is moves_on or status is SKIPPED:
                node._current += 1
                if status is moves_on and fresh and node._current < len(children):
                    node.status = RUNNING
                    return RUNNING
                continue
            node._current = 0
            _reset(node, world)
            node.status = status
            return status
        node._current = 0
        _reset(node, world)
        node.status = status = SUCCESS if moves_on is SUCCESS else FAILURE
        return status


class AsyncSequence(Sequence):
    """BT.CPP AsyncSequence: a memory Sequence that yields (RUNNING) after each fresh
    child SUCCESS that is not the last; FAILURE rewinds and halts, as in Sequence."""

    __slots__ = ()
    kind = "AsyncSequence"

    def __init__(self, children: list[Node] | None = None, name: str = "") -> None:
        super().__init__(children, name, memory=True)

    def tick(self, world: World) -> Status:
        """Resume the remembered child and move on after SUCCESS or SKIPPED, yielding after a
        fresh SUCCESS so one tick runs at most one synchronous child."""
        return _Async.run(self, world, SUCCESS)


class AsyncFallback(Fallback):
    """BT.CPP AsyncFallback: a memory Fallback that yields (RUNNING) after each fresh
    child FAILURE that is not the last; SUCCESS rewinds and halts."""

    __slots__ = ()
    kind = "AsyncFallback"

    def __init__(self, children: list[Node] | None = None, name: str = "") -> None:
        super().__init__(children, name, memory=True)

    def tick(self, world: World) -> Status:
        """Resume the remembered child and move on after FAILURE or SKIPPED, yielding after a
        fresh FAILURE so one tick runs at most one synchronous child."""
        return _Async.run(self, world, FAILURE)


class ParallelAll(Composite):
    """BT.CPP ParallelAll: ticks every unfinished child until all have finished.

    Then it halts what is left and returns FAILURE if at least `max_failures` children
    failed (negative counts from the number of children), else SUCCESS; RUNNING before.
    """

    __slots__ = ("_done", "_failures", "ports")
    kind = "ParallelAll"

    def __init__(self, children: list[Node] | None, ports: Ports, name: str = "") -> None:
        super().__init__(children, name)
        self.ports = ports
        self._done: set[int] = set()
        self._failures = 0

    def tick(self, world: World) -> Status:
        """Tick each unfinished child; `max_failures` is read every tick, so a `{key}` value may
        change it. RUNNING while a child neither finished nor was skipped this tick, SKIPPED
        when all were skipped; the verdict clears the counts and resets the children."""
        children = self.children
        threshold = self.ports.int("max_failures")
        if threshold < 0:
            threshold = max(len(children) + threshold + 1, 0)
        skipped = 0
        for i, child in enumerate(children):
            if i in self._done:
                continue
            status = child.tick(world)
            if status is SUCCESS or status is FAILURE:
                self._done.add(i)
                self._failures += status is FAILURE
            elif status is SKIPPED:
                skipped += 1
        if skipped == len(children):
            self.status = RUNNING  # what BT.CPP set before ticking the children
            return SKIPPED
        if skipped + len(self._done) < len(children):
            self.status = RUNNING
            return RUNNING
        status = FAILURE if self._failures >= threshold else SUCCESS
        self._done, self._failures = set(), 0
        _reset(self, world)
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Forget which children finished and how many failed, so the next tick starts a fresh
        run; then halt the children."""
        self._done, self._failures = set(), 0
        super().halt(world)


class IfThenElse(Composite):
    """BT.CPP IfThenElse: child 0 is the condition, ticked once per run (not reactive).

    Its SUCCESS picks child 1, its FAILURE child 2 (or returns FAILURE with only two
    children), RUNNING is returned. The picked branch is ticked until it finishes;
    then every child is reset and its status returned.
    """

    __slots__ = ("_branch",)
    kind = "IfThenElse"

    def __init__(self, children: list[Node] | None = None, name: str = "") -> None:
        super().__init__(children, name)
        self._branch = 0

    def tick(self, world: World) -> Status:
        """Ask the condition only while no branch is chosen, then tick the chosen branch until it
        finishes. A SKIPPED condition raises NodeError, as BT.CPP 4.8 stops on it too."""
        children = self.children
        if self._branch == 0:
            status = children[0].tick(world)
            if status is SKIPPED:
                raise NodeError("IfThenElse: its condition was skipped, which BT.CPP 4.8 "
                                "stops on as an error too")
            if status is SUCCESS:
                self._branch = 1
            elif status is FAILURE and len(children) == 3:
                self._branch = 2
            else:
                self.status = status
                return status
        status = children[self._branch].tick(world)
        if status is not RUNNING:
            self._branch = 0
            _reset(self, world)
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Drop the chosen branch, so the next tick asks the condition again; then halt the
        children."""
        self._branch = 0
        super().halt(world)


class WhileDoElse(Composite):
    """BT.CPP WhileDoElse: the reactive IfThenElse; the condition is ticked every tick.

    Condition SUCCESS: halt child 2, tick child 1. FAILURE: halt child 1, tick child 2
    (FAILURE with only two children). RUNNING: returned. A finished branch resets all.
    """

    __slots__ = ()
    kind = "WhileDoElse"

    def tick(self, world: World) -> Status:
        """Tick the condition every tick and halt the branch it no longer picks before ticking
        the other. A SKIPPED condition counts as no branch: FAILURE, with the children reset."""
        children = self.children
        condition = children[0].tick(world)
        if condition is RUNNING:
            self.status = RUNNING
            return RUNNING
        status: Status = FAILURE
        if condition is SUCCESS:
            if len(children) == 3 and children[2].status is not IDLE:
                children[2].halt(world)
            status = children[1].tick(world)
        elif condition is FAILURE and len(children) == 3:
            if children[1].status is not IDLE:
                children[1].halt(world)
            status = children[2].tick(world)
        if status is not RUNNING:
            _reset(self, world)
        self.status = status
        return status


def _same_case(value: str, case: str, enums: dict[str, int]) -> bool:
    """BT.CPP's string equality for Switch: the same text, enum or number."""
    if value == case:
        return True
    if value in enums or case in enums:
        value, case = str(enums.get(value, value)), str(enums.get(case, case))
    try:
        return abs(to_number(value, "") - to_number(case, "")) <= 1.1920929e-07
    except Exception:  # noqa: BLE001 -- not two numbers: simply no match
        return False


class Switch(Composite):
    """BT.CPP Switch2..Switch6: ticks the child of the first `case_i` equal to `variable`,
    or the last child (default) when none matches or `variable` is unset.

    A child that was RUNNING and is no longer picked is halted first. A finished child
    resets every child.
    """

    __slots__ = ("_running", "cases", "ports")
    kind = "Switch"

    def __init__(self, children: list[Node] | None, cases: int, ports: Ports,
                 name: str = "") -> None:
        super().__init__(children, name)
        self.cases = cases
        self.ports = ports
        self._running = -1

    def tick(self, world: World) -> Status:
        """Read `variable` and the `case_i` ports now (an unset variable picks the default) and
        tick the first match: equal text, enum value or number within a float epsilon. A
        SKIPPED child is passed on without resetting the others."""
        match = self.cases
        try:
            variable = self.ports.text("variable")
        except Exception:  # noqa: BLE001 -- an unset variable selects the default, as in BT.CPP
            variable = None
        if variable is not None:
            for i in range(self.cases):
                port = f"case_{i + 1}"
                if port in self.ports.values and _same_case(variable, self.ports.text(port),
                                                                    self.ports.board.enums):
                    match = i
                    break
        children = self.children
        if self._running not in (-1, match):
            children[self._running].halt(world)
        status = children[match].tick(world)
        if status is RUNNING:
            self._running = match
        else:
            self._running = -1
            if status is not SKIPPED:
                _reset(self, world)
        self.status = RUNNING if status is SKIPPED else status
        return status

    def halt(self, world: World) -> None:
        """Forget which child was running, then halt the children."""
        self._running = -1
        super().halt(world)


class TryCatch(Composite):
    """BT.CPP 4.10 TryCatch: children 1..N-1 run as a memory Sequence (the try block);
    if one fails, the last child (the catch block) runs to its end and the node
    returns FAILURE whatever it answered. SKIPPED try children are passed over. With
    `catch_on_halt`, halting the node while the try block runs ticks the catch child
    once (halting it if it answers RUNNING).

    Newer than the BT.CPP the tests load: written from its documentation, not checked
    tick by tick.
    """

    __slots__ = ("_catching", "_current", "ports")
    kind = "TryCatch"

    def __init__(self, children: list[Node] | None, ports: Ports, name: str = "") -> None:
        super().__init__(children, name)
        self.ports = ports
        self._current = 0
        self._catching = False

    def tick(self, world: World) -> Status:
        """Run the try children from where the last tick stopped; after a FAILURE only the catch
        child is ticked, until it finishes, and the answer is FAILURE whatever it said.
        SUCCESS when the whole try block succeeds."""
        children = self.children
        if not self._catching:
            while self._current < len(children) - 1:
                status = children[self._current].tick(world)
                if status is RUNNING:
                    self.status = RUNNING
                    return RUNNING
                if status is FAILURE:
                    self._catching = True
                    break
                self._current += 1
            else:
                self._current = 0
                _reset(self, world)
                self.status = SUCCESS
                return SUCCESS
        status = children[-1].tick(world)
        if status is RUNNING:
            self.status = RUNNING
            return RUNNING
        self._current, self._catching = 0, False
        _reset(self, world)
        self.status = FAILURE
        return FAILURE

    def halt(self, world: World) -> None:
        """Rewind and halt the children. With `catch_on_halt`, a halt that cuts the try block
        short then ticks the catch child once (halting it if RUNNING); the node ends IDLE."""
        in_try = self.status is RUNNING and not self._catching
        self._current, self._catching = 0, False
        super().halt(world)
        if in_try and self.ports.bool("catch_on_halt"):
            catch = self.children[-1]
            if catch.tick(world) is RUNNING:
                catch.halt(world)
        self.status = IDLE


__all__ = ["AsyncFallback", "AsyncSequence", "IfThenElse", "ParallelAll", "SequenceWithMemory",
           "Switch", "TryCatch", "WhileDoElse"]
