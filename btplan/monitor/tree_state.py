"""The growing tree as BehaviorTree.CPP describes a tree it runs.

Groot2 and FileLogger2 name nodes by a 16-bit `_uid`. BT.CPP numbers the nodes of a
tree 1, 2, ... depth first when it builds the tree, and the tree never changes after.
btplan's tree grows while the robot acts, so the numbering is kept: a node keeps its
uid for the whole run, the nodes an expansion adds get the next free ones (depth first
among themselves), and the tree's 16-byte UUID changes with every growth, so that a
client knows to fetch the tree again. A tree that never grows is numbered exactly as
BT.CPP numbers it.

Statuses follow BT.CPP's publisher: 0 idle, 1 running, 2 success, 3 failure, 4
skipped, and 10 + the last status for a node reset to idle. BT.CPP's reactive
composites halt every child but the running one, reset all of them when they finish,
and the tree resets the root when it finishes: after a tick, only the running branch
is not idle, and Groot2 draws the others from where they had been.
"""

from __future__ import annotations

import uuid
from collections.abc import Iterable, Mapping

from btplan.acting.records import TickRecord
from btplan.bt.formats.btcpp import dump_running_xml
from btplan.bt.leaves import Leaf
from btplan.bt.node import Node
from btplan.bt.status import Status
from btplan.bt.tree import BehaviorTree

__all__ = ["CODES", "IDLE_FROM", "MAX_UID", "TreeState"]

CODES = {Status.IDLE: 0, Status.RUNNING: 1, Status.SUCCESS: 2, Status.FAILURE: 3,
         Status.SKIPPED: 4}
"""BT.CPP's NodeStatus values."""

IDLE_FROM = 10
"""Added to the last status of a node reset to idle (BT.CPP's IDLE_FROM_SUCCESS, ...)."""

MAX_UID = 0xFFFF
"""Uids are 16 bits on the wire: nodes past this many are not shown."""


class TreeState:
    """The tree after each tick: uids, XML, status codes, transitions and facts."""

    def __init__(self, name: str = "MainTree", facts: Iterable[str] = ()) -> None:
        self.name = name
        self.uuid = uuid.uuid4().bytes
        self.tick = 0
        self.versions = 0
        self.reshaped = False
        """Whether the last update changed the tree (a growth, a move, a new root)."""
        self._root: Node | None = None
        self._xml: tuple[int, str] | None = None
        self.facts: set[str] = set(facts)
        self._uids: dict[int, int] = {}
        self._kept: list[Node] = []
        """Every node numbered, so that no id() is reused by a later node."""
        self._order: list[Node] = []
        self._shape: list[int] = []
        self._controls: set[int] = set()
        self._running: set[int] = set()
        self._buffer = bytearray()
        self._offsets: dict[int, int] = {}
        """Where each uid's status code sits in the status buffer."""
        self._codes: dict[int, int] = {}
        self.dropped = 0
        """Nodes past MAX_UID, which no client sees."""

    # --- after every tick ----------------------------------------------------------------

    def update(self, root: Node, reached: Mapping[int, Status],
               record: TickRecord | None = None) -> list[tuple[int, int]]:
        """Take in one tick; the transitions (uid, BT.CPP status) it made, in order.

        The tree changes only where the loop expands (conflict resolution moves
        subtrees then) or takes a tree planned offline, and every such tick reports
        expansions: the tree is walked again on those ticks only."""
        if record is not None:
            self.tick = record.tick
            self.facts.difference_update(record.removed)
            self.facts.update(record.added)
        self.reshaped = False
        if record is None or record.expansions or not self._order or (
                root is not self._order[0]):
            self._reshape(root)
        return self._statuses(reached)

    def _reshape(self, root: Node) -> None:
        nodes = root.walk()
        shape = [id(n) for n in nodes]
        if shape == self._shape:
            return
        self._shape = shape
        self._number(nodes)
        self._order = [n for n in nodes if id(n) in self._uids]
        self._controls = {self._uids[id(n)] for n in self._order if not isinstance(n, Leaf)}
        self._buffer = bytearray()
        self._offsets = {}
        for node in self._order:
            uid = self._uids[id(node)]
            self._buffer += uid.to_bytes(2, "little")
            self._offsets[uid] = len(self._buffer)
            self._buffer.append(self._codes.get(uid, 0))
        self._root = root
        self.uuid = uuid.uuid4().bytes
        self.versions += 1
        self.reshaped = True

    def _number(self, nodes: list[Node]) -> None:
        """Give the new nodes the next uids."""
        for node in nodes:
            if id(node) in self._uids:
                continue
            if len(self._kept) >= MAX_UID:
                self.dropped += 1
                continue
            self._kept.append(node)
            self._uids[id(node)] = len(self._kept)

    def _statuses(self, reached: Mapping[int, Status]) -> list[tuple[int, int]]:
        """The codes after this tick, and the transitions that led there in BT.CPP:
        a reached node goes to its status (unless it stays RUNNING), and every node
        that is not RUNNING at the end of the tick is reset to idle (its parent halts
        it, or the tree resets the root), which is a transition to 0 of its own. A
        control node sets itself RUNNING as its tick starts, whatever it returns.

        Only the nodes the tick reached and those RUNNING before it can change, so
        only they are looked at: the rest of a large tree costs nothing per tick."""
        transitions: list[tuple[int, int]] = []
        codes, controls, uids = self._codes, self._controls, self._uids
        running = CODES[Status.RUNNING]
        was_running, self._running = self._running, set()
        for key, status in reached.items():
            uid = uids.get(key)
            if uid is None:
                continue
            before = running if uid in was_running else 0
            code = CODES[status]
            if before != running and uid in controls:  # set RUNNING as they start
                transitions.append((uid, running))
                before = running
            if code != before:
                transitions.append((uid, code))
            if code == running:
                self._running.add(uid)
            else:
                transitions.append((uid, 0))
                code += IDLE_FROM
            self._set(uid, code)
        for uid in was_running - self._running:
            if codes.get(uid) == running:  # halted without being reached
                transitions.append((uid, 0))
                self._set(uid, IDLE_FROM + running)
        return transitions

    def _set(self, uid: int, code: int) -> None:
        self._codes[uid] = code
        at = self._offsets.get(uid)
        if at is not None:
            self._buffer[at] = code

    # --- what clients read -----------------------------------------------------------------

    @property
    def xml(self) -> str:
        """The tree as BT.CPP writes a tree it runs (made when first asked for after a
        change: only Groot2 and replay files need it)."""
        if self._root is None:
            return ""
        if self._xml is None or self._xml[0] != self.versions:
            self._xml = (self.versions, dump_running_xml(BehaviorTree(self._root, self.name),
                                                         self.uid))
        return self._xml[1]

    def rows(self) -> list[tuple[int, int, str, str]]:
        """The tree, depth first: (uid, the parent's uid or 0, kind, name) per node."""
        parents: dict[int, int] = {}
        out = []
        for node in self._order:
            uid = self._uids[id(node)]
            out.append((uid, parents.get(uid, 0), node.kind, node.name))
            for child in node.children:
                child_uid = self._uids.get(id(child))
                if child_uid is not None:
                    parents[child_uid] = uid
        return out

    def uid_of(self, key: int) -> int:
        """The uid of the node whose id() is `key` (0: none)."""
        return self._uids.get(key, 0)

    def uid(self, node: Node) -> int:
        """The node's uid (0 for a node past MAX_UID)."""
        return self.uid_of(id(node))

    def nodes(self) -> list[tuple[int, Node]]:
        """The nodes of the tree, depth first, with their uids."""
        return [(self._uids[id(n)], n) for n in self._order]

    def status_buffer(self) -> bytes:
        """BT.CPP's status buffer: per node, depth first, its uid (2 bytes, little
        endian) and its status code (1 byte)."""
        return bytes(self._buffer)

    def code(self, uid: int) -> int:
        """The node's status code after the last tick (0 for a node never reached)."""
        return self._codes.get(uid, 0)
