"""Per-tick traces: which nodes a tick reached, their statuses, which actions started or halted.

Zero cost when off: a tree without a recorder ticks its plain nodes. During a
recorded tick each node's class is switched to a traced subclass with the same slots
(a `__class__` swap), whose tick notes entry and exit on the channel passed down as
the world; after the tick every node gets its plain class back, so between ticks
(when the planner edits the tree, or code tests `type(node) is Sequence`) a recorded
tree looks exactly like any other. The tick engine itself carries no hooks, so
tracing never slows down the acting loop that does not ask for it.

Node ids (`n0`, `n1`, ...) are positions in a depth-first, left-to-right walk, so the
same tree gives the same ids on every run; they match the DOT export's node names.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Mapping
from typing import TYPE_CHECKING, Any, TextIO

from btplan.bt.node import Node
from btplan.bt.status import RUNNING, Status
from btplan.bt.world import LeafKey, World
from btplan.io import write_atomic
from btplan.records import record

if TYPE_CHECKING:
    from btplan.bt.tree import BehaviorTree


def node_ids(root: Node) -> dict[int, str]:
    """Stable ids by depth-first position, keyed by `id(node)`."""
    return {id(node): f"n{i}" for i, node in enumerate(root.walk())}


@record(frozen=True, slots=True)
class NodeTick:
    """One node reached by one tick, in the order the tick reached it."""

    id: str
    kind: str
    name: str
    status: Status


@record(frozen=True, slots=True)
class TickTrace:
    """What one tick of the whole tree did; `started`/`halted` hold action node ids."""

    tick: int
    status: Status
    nodes: tuple[NodeTick, ...]
    started: tuple[str, ...] = ()
    halted: tuple[str, ...] = ()

    def statuses(self) -> dict[str, Status]:
        """Status of every node this tick reached, by node id (for colouring exports)."""
        return {n.id: n.status for n in self.nodes}

    def to_dict(self) -> dict[str, Any]:
        """The trace as plain JSON values, statuses by name: what one line of a `--trace`
        file holds."""
        return {
            "tick": self.tick,
            "status": self.status.value,
            "nodes": [{"id": n.id, "kind": n.kind, "name": n.name, "status": n.status.value}
                      for n in self.nodes],
            "started": list(self.started),
            "halted": list(self.halted),
        }

    def to_json(self) -> str:
        """`to_dict` as one compact JSON line; names outside ASCII are kept as they are."""
        import json  # here: a plan run records no traces and writes no JSON lines

        return json.dumps(self.to_dict(), separators=(",", ":"), ensure_ascii=False)


def traces_to_jsonl(traces: Iterable[TickTrace]) -> str:
    """One JSON object per line and per tick, for `--trace FILE.jsonl`."""
    return "".join(t.to_json() + "\n" for t in traces)


def write_jsonl(path: str, traces: Iterable[TickTrace]) -> None:
    """Write a JSON-lines trace file all at once (`-` is standard output)."""
    write_atomic(path, traces_to_jsonl(traces))


class _Channel:
    """The world as traced nodes see it: forwards every call, collects what happened."""

    __slots__ = ("entries", "halted", "ids", "started", "world")

    def __init__(self, world: World, ids: dict[int, str]) -> None:
        self.world = world
        self.ids = ids
        self.entries: list[list[Any]] = []
        self.started: list[str] = []
        self.halted: list[str] = []

    def check(self, key: LeafKey) -> bool:
        return self.world.check(key)

    def start(self, key: LeafKey) -> Status:
        return self.world.start(key)

    def step(self, key: LeafKey) -> Status:
        return self.world.step(key)

    def halt(self, key: LeafKey) -> None:
        self.world.halt(key)


_TRACED: dict[type[Node], type[Node]] = {}
_ORIGINAL: dict[type[Node], type[Node]] = {}


def _traced_class(cls: type[Node]) -> type[Node]:
    """The traced twin of a node class: same slots, tick and halt that report to the channel."""
    if cls in _ORIGINAL:
        return cls
    if cls in _TRACED:
        return _TRACED[cls]
    base_tick: Callable[[Node, World], Status] = cls.tick
    base_halt: Callable[[Node, World], None] = cls.halt
    is_action = cls.kind == "Action"

    def tick(self: Node, world: World) -> Status:
        if type(world) is not _Channel:
            return base_tick(self, world)
        node_id = world.ids.get(id(self), "?")
        entry: list[Any] = [node_id, self, None]
        world.entries.append(entry)
        was = self.status
        status = base_tick(self, world)
        entry[2] = status
        if is_action and was is not RUNNING:
            world.started.append(node_id)
        return status

    def halt(self: Node, world: World) -> None:
        if is_action and self.status is RUNNING and type(world) is _Channel:
            world.halted.append(world.ids.get(id(self), "?"))
        base_halt(self, world)

    twin = type(cls.__name__, (cls,), {"__slots__": (), "tick": tick, "halt": halt,
                                       "__module__": cls.__module__,
                                       "__qualname__": cls.__qualname__})
    _TRACED[cls], _ORIGINAL[twin] = twin, cls
    return twin


def _restore(nodes: list[Node]) -> None:
    """Give every node its plain class back."""
    for node in nodes:
        plain = _ORIGINAL.get(type(node))
        if plain is not None:
            node.__class__ = plain


class TickRecorder:
    """Records every tick of the trees it is attached to.

    `keep` bounds how many traces stay in memory (None keeps all); `sink`, if given,
    receives each trace as one JSON line as soon as the tick ends.
    """

    def __init__(self, keep: int | None = None, sink: TextIO | None = None) -> None:
        self.traces: deque[TickTrace] = deque(maxlen=keep)
        self.sink = sink
        self.last_nodes: list[Node] = []
        """The nodes of the latest recorded tick, in the order of its ids (`n0`, `n1`, ...):
        the tree may have been replaced or grown since, and the ids are this tick's."""

    def attach(self, tree: BehaviorTree) -> None:
        """Record the tree's ticks from its next tick on, replacing any recorder it had; node
        classes are swapped only during each recorded tick."""
        tree.recorder = self

    def detach(self, tree: BehaviorTree) -> None:
        """Stop recording this tree."""
        tree.recorder = None
        _restore(tree.nodes())

    @property
    def last(self) -> TickTrace | None:
        """The newest trace kept, or None before the first recorded tick."""
        return self.traces[-1] if self.traces else None

    def tick(self, tree: BehaviorTree, world: World) -> Status:
        """Tick `tree.root` through a recording channel; called by `BehaviorTree.tick`."""
        nodes = list(tree.nodes())
        self.last_nodes = nodes
        for node in nodes:
            cls = type(node)
            if cls not in _ORIGINAL:
                node.__class__ = _traced_class(cls)
        channel = _Channel(world, {id(n): f"n{i}" for i, n in enumerate(nodes)})
        try:
            status = tree.root.tick(channel)
        finally:
            _restore(nodes)
        trace = TickTrace(
            tick=tree.ticks, status=status,
            nodes=tuple(NodeTick(i, n.kind, n.name, s) for i, n, s in channel.entries),
            started=tuple(channel.started), halted=tuple(channel.halted),
        )
        self.traces.append(trace)
        if self.sink is not None:
            self.sink.write(trace.to_json() + "\n")
        return status


def last_statuses(root: Node) -> Mapping[str, Status]:
    """Each node's last status by id: what a tree looks like after its latest tick."""
    return {f"n{i}": node.status for i, node in enumerate(root.walk())}
