"""The other decorators of BehaviorTree.CPP 4: loops, gates and one-shot nodes.

Times are counted in ticks, as in btplan's Timeout: a BT.CPP delay of `msec`
milliseconds becomes ceil(msec / tick length) ticks when the tree is read. Ports are
read through the node's blackboard on the tick that needs them, as BT.CPP does.
"""

from __future__ import annotations

from btplan.bt.blackboard import NodeError, Ports, Value, as_text, to_bool, to_number
from btplan.bt.decorators import Decorator, Retry
from btplan.bt.node import Node
from btplan.bt.script import Script
from btplan.bt.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.world import World

STATUS_NAMES = {"SUCCESS": SUCCESS, "FAILURE": FAILURE, "RUNNING": RUNNING, "SKIPPED": SKIPPED,
                "IDLE": IDLE}


def status_port(ports: Ports, port: str) -> Status:
    """A port that names a status (`else`, `if_empty`) as that Status; other text is a
    NodeError naming the node and port."""
    text = ports.text(port)
    if text not in STATUS_NAMES:
        raise NodeError(f"{ports.owner}.{port}: {text!r} is not SUCCESS, FAILURE, RUNNING "
                        "or SKIPPED")
    return STATUS_NAMES[text]


class Repeat(Decorator):
    """BT.CPP Repeat: runs the child `num_cycles` times in a row (-1: for ever).

    Child SUCCESS counts one cycle; after a fresh child's SUCCESS the node yields
    (RUNNING) until the next tick, after a child that had been RUNNING it goes on at
    once. FAILURE: FAILURE, and the count restarts. RUNNING: RUNNING. All cycles done:
    SUCCESS, and the count restarts.
    """

    __slots__ = ("_count", "ports")
    kind = "Repeat"

    def __init__(self, child: Node | None, ports: Ports, name: str = "") -> None:
        super().__init__(child, name)
        self.ports = ports
        self._count = 0

    def tick(self, world: World) -> Status:
        """Read `num_cycles` on this tick and run the cycles left (see the class). A SKIPPED
        child is passed on, with the node itself marked RUNNING."""
        cycles = self.ports.int("num_cycles")
        child = self.children[0]
        while cycles == -1 or self._count < cycles:
            fresh = child.status is not RUNNING
            status = child.tick(world)
            if status is SUCCESS:
                self._count += 1
                if fresh and (cycles == -1 or self._count < cycles):
                    self.status = RUNNING
                    return RUNNING
            elif status is FAILURE:
                self._count = 0
                self.status = FAILURE
                return FAILURE
            else:
                self.status = RUNNING if status is SKIPPED else status
                return status
        self._count = 0
        self.status = SUCCESS
        return SUCCESS

    def halt(self, world: World) -> None:
        """Restart the cycle count, so the next run does all `num_cycles` again; then halt the
        child."""
        self._count = 0
        super().halt(world)


class KeepRunningUntilFailure(Decorator):
    """Child SUCCESS: RUNNING (and it starts again next tick). FAILURE: FAILURE."""

    __slots__ = ()
    kind = "KeepRunningUntilFailure"

    def tick(self, world: World) -> Status:
        """RUNNING after a child SUCCESS or SKIPPED, so the child starts again next tick; only
        the child's FAILURE ends it."""
        status = self.children[0].tick(world)
        if status is SUCCESS or status is SKIPPED:  # BT.CPP 4.8 keeps running on a skip
            status = RUNNING
        self.status = status
        return status


class RunOnce(Decorator):
    """Runs the child until it finishes once; afterwards SKIPPED (then_skip, the default)
    or the status it finished with, without ticking it again."""

    __slots__ = ("_result", "ports")
    kind = "RunOnce"

    def __init__(self, child: Node | None, ports: Ports, name: str = "") -> None:
        super().__init__(child, name)
        self.ports = ports
        self._result: Status | None = None

    def tick(self, world: World) -> Status:
        """Tick the child until it first finishes and remember that status; later ticks answer
        SKIPPED or, with `then_skip` false, the remembered status. A halt does not forget it."""
        if self._result is not None:
            if self.ports.bool("then_skip"):
                return SKIPPED
            self.status = self._result
            return self._result
        status = self.children[0].tick(world)
        if status is SUCCESS or status is FAILURE:
            self._result = status
        self.status = status
        return status


class Precondition(Decorator):
    """BT.CPP 4.8 Precondition: the `if` script is checked when the child is not running.

    True: tick the child and return its status. False: return `else` (FAILURE by
    default) without ticking the child. While the child is RUNNING the script is not
    checked again.
    """

    __slots__ = ("_running", "ports", "script")
    kind = "Precondition"

    def __init__(self, child: Node | None, ports: Ports, script: Script, name: str = "") -> None:
        super().__init__(child, name)
        self.ports = ports
        self.script = script
        self._running = False

    def tick(self, world: World) -> Status:
        """Check the `if` script only when the child is not running: false answers `else` (read
        on every tick) without ticking the child, true runs the child to its end."""
        otherwise = status_port(self.ports, "else")
        if not self._running and not self.script.holds(self.ports.board):
            self.status = RUNNING if otherwise is SKIPPED else otherwise
            return otherwise
        self._running = True
        status = self.children[0].tick(world)
        if status is not RUNNING:
            self._running = False
        self.status = RUNNING if status is SKIPPED else status
        return status

    def halt(self, world: World) -> None:
        """Forget that the child was running, so the next tick checks the script again; then
        halt the child."""
        self._running = False
        super().halt(world)


class Delay(Decorator):
    """Waits `ticks` ticks (answering RUNNING), then ticks the child until it finishes."""

    __slots__ = ("_waited", "ticks")
    kind = "Delay"

    def __init__(self, child: Node | None, ticks: int, name: str = "") -> None:
        super().__init__(child, name)
        self.ticks = ticks
        self._waited = -1

    def tick(self, world: World) -> Status:
        """RUNNING for the first `ticks` ticks of a run, then tick the child; once the child
        finishes, the next tick starts a new delay."""
        self._waited += 1
        if self._waited < self.ticks:
            self.status = RUNNING
            return RUNNING
        status = self.children[0].tick(world)
        if status is not RUNNING:
            self._waited = -1
        self.status = RUNNING if status is SKIPPED else status
        return status

    def halt(self, world: World) -> None:
        """Restart the delay for the next run; then halt the child."""
        self._waited = -1
        super().halt(world)


class Loop(Decorator):
    """BT.CPP LoopInt/LoopDouble/LoopString/LoopBool: one child run per queue item.

    When the child is not RUNNING, the next item is taken from `queue` (a literal
    `a;b;c`, restarted each time the node starts, or a blackboard entry holding such a
    text, which is consumed) and written to `value`. An empty queue answers `if_empty`
    (SUCCESS by default). Child FAILURE: FAILURE; otherwise RUNNING, so the next tick
    takes the next item.
    """

    __slots__ = ("_child_running", "_queue", "item", "ports")
    kind = "Loop"

    def __init__(self, child: Node | None, ports: Ports, item: str, name: str = "") -> None:
        super().__init__(child, name)
        self.ports = ports
        self.item = item
        self._queue: list[str] = []
        self._child_running = False

    def _convert(self, text: str) -> Value:
        what = f"{self.ports.owner}.value"
        if self.item == "Int":
            number = to_number(text, what)
            return int(number) if number.is_integer() else number
        if self.item == "Double":
            return to_number(text, what)
        if self.item == "Bool":
            return to_bool(text, what)
        return text

    def _pop(self) -> str | None:
        raw = self.ports.values.get("queue", "")
        key = self.ports.key("queue") if raw.startswith("{") else None
        if key is None:
            if self.status is not RUNNING:
                self._queue = [x for x in raw.split(";") if x.strip()]
            return self._queue.pop(0).strip() if self._queue else None
        if not self.ports.board.has(key):
            return None
        items = [x for x in as_text(self.ports.board.get(key)).split(";") if x.strip()]
        if not items:
            return None
        self.ports.board.set(key, ";".join(items[1:]))
        return items[0].strip()

    def tick(self, world: World) -> Status:
        """When the child is not running, take the next queue item into `value`, then tick the
        child: FAILURE ends the loop, anything else is RUNNING. An empty queue answers
        `if_empty`."""
        if self.status is not RUNNING:
            self._child_running = False
        if not self._child_running:
            item = self._pop()
            if item is None:
                status = status_port(self.ports, "if_empty")
                self.status = RUNNING if status is SKIPPED else status
                return status
            if "value" in self.ports.values:
                self.ports.write("value", self._convert(item))
        status = self.children[0].tick(world)
        self._child_running = status is RUNNING
        status = FAILURE if status is FAILURE else RUNNING
        self.status = status
        return status

    def halt(self, world: World) -> None:
        """Forget the running child, so the next tick takes a new item (and a literal queue
        starts again); then halt the child."""
        self._child_running = False
        super().halt(world)


class WhenUpdated(Decorator):
    """BT.CPP SkipUnlessUpdated (`waits=False`) and WaitValueUpdate (`waits=True`).

    On a fresh start, if the `entry` was not written since the last start the node
    answers SKIPPED (or RUNNING, to wait); otherwise it ticks the child to its end.
    """

    __slots__ = ("_active", "_seen", "ports", "waits")
    kind = "WhenUpdated"

    def __init__(self, child: Node | None, ports: Ports, waits: bool, name: str = "") -> None:
        super().__init__(child, name)
        self.ports = ports
        self.waits = waits
        self._seen = 0
        self._active = False

    def tick(self, world: World) -> Status:
        """On a fresh start, compare the entry's write count with the one seen at the last
        start: unchanged answers SKIPPED (RUNNING when `waits`) without ticking the child;
        changed runs the child to its end."""
        if not self._active:
            seq = self.ports.board.sequence(self.ports.key("entry"))
            if seq == self._seen:
                if self.waits:
                    self.status = RUNNING
                return RUNNING if self.waits else SKIPPED
            self._seen = seq
            self._active = True
        status = self.children[0].tick(world)
        if status is not RUNNING:
            self._active = False
        self.status = RUNNING if status is SKIPPED else status
        return status

    def halt(self, world: World) -> None:
        """End the current run, so the next tick looks at the entry again; the write count seen
        is kept, so a halt does not make an old write look new."""
        self._active = False
        super().halt(world)


__all__ = ["STATUS_NAMES", "Delay", "KeepRunningUntilFailure", "Loop", "Precondition", "Repeat",
           "RunOnce", "WhenUpdated", "status_port"]


class BoardRetry(Retry):
    """BT.CPP RetryUntilSuccessful whose `num_attempts` is a blackboard value
    (`num_attempts="{num_locs}"`), read on every tick as BT.CPP reads its input port.

    A value that allows no attempt (below 1, other than -1 for ever) counts as one.
    """

    __slots__ = ("ports",)

    def __init__(self, child: Node | None, ports: Ports, name: str = "") -> None:
        super().__init__(child, 1, name)
        self.ports = ports

    def tick(self, world: World) -> Status:
        """Read `num_attempts` from the blackboard, then tick as Retry; failures counted so far
        are kept, so a changed value applies to the run under way."""
        attempts = self.ports.int("num_attempts")
        self.attempts = attempts if attempts >= 1 or attempts == -1 else 1
        return super().tick(world)
