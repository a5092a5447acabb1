"""One run, watched: the tree's state after every tick, handed to each monitor.

A RunMonitor is the run's tick view (btplan.acting.recorder.TickView): after every
tick it brings the TreeState up to date once and gives every monitor (the Groot2
server, the `.btlog` writer, the browser view) the same TickUpdate. It only reads
what the run reports, so a watched run acts exactly like one that is not.

The update also makes the tick's line for `--trace`: the tick's record, and beside it
what a viewer needs to draw the tree at that tick (docs/cli.md, "The trace"):

- `tree`, on the first tick and on every tick that changed the tree: every node depth
  first as `[uid, parent uid (0 for the root), kind, name]`;
- `statuses`: `[uid, status]` for every node the tick reached, in the order it did;
- `facts_at_start`, on the first line: the world's facts before the first tick.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping, Sequence
from functools import cached_property
from typing import Any, Protocol

from btplan.acting.records import TickRecord
from btplan.bt.node import Node
from btplan.bt.status import Status
from btplan.monitor.tree_state import TreeState

__all__ = ["Monitor", "RunMonitor", "TickUpdate"]


class TickUpdate:
    """What one tick changed, as every monitor and the trace see it."""

    def __init__(self, record: TickRecord, transitions: list[tuple[int, int]],
                 statuses: list[tuple[int, str]], tree: list[tuple[int, int, str, str]] | None,
                 facts_at_start: list[str] | None) -> None:
        self.record = record
        self.transitions = transitions
        self.statuses = statuses
        self.tree = tree
        """The tree's rows when this tick changed it (or is the first), else None."""
        self.facts_at_start = facts_at_start

    @cached_property
    def line(self) -> str:
        """The tick's trace line (module docstring), without its newline."""
        out: dict[str, Any] = self.record.to_dict()
        out["statuses"] = self.statuses
        if self.tree is not None:
            out["tree"] = self.tree
        if self.facts_at_start is not None:
            out["facts_at_start"] = self.facts_at_start
        return json.dumps(out, separators=(",", ":"), ensure_ascii=False)


class Monitor(Protocol):
    """What watches a run: takes each tick's update, and ends with the run."""

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        """Take in one tick (called in the run's thread, after the tick)."""

    def close(self) -> None:
        """The run ended, however it ended: finish what is written, free what is held."""


class RunMonitor:
    """The tick view that feeds `monitors` (module docstring)."""

    def __init__(self, monitors: Sequence[Monitor], name: str = "MainTree",
                 facts: Iterable[str] = ()) -> None:
        self.monitors = list(monitors)
        self.facts_at_start = sorted(facts)
        self.state = TreeState(name, self.facts_at_start)
        self.last: TickUpdate | None = None

    def __call__(self, root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
        self.update(root, reached, record)

    def update(self, root: Node, reached: Mapping[int, Status],
               record: TickRecord) -> TickUpdate:
        """Take in one tick, hand it to every monitor, and return it."""
        first = self.last is None
        transitions = self.state.update(root, reached, record)
        uid_of = self.state.uid_of
        statuses = [(uid_of(key), status.value) for key, status in reached.items()]
        update = TickUpdate(record, transitions, statuses,
                            self.state.rows() if self.state.reshaped or first else None,
                            self.facts_at_start if first else None)
        self.last = update
        for monitor in self.monitors:
            monitor.publish(self.state, update)
        return update

    def close(self) -> None:
        """Close every monitor, each even when another one fails; the first error is
        raised after."""
        failed: BaseException | None = None
        for monitor in self.monitors:
            try:
                monitor.close()
            except BaseException as error:  # noqa: BLE001 (raised below, once all closed)
                failed = failed or error
        if failed is not None:
            raise failed
