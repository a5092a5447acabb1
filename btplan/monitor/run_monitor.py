"""One run, watched: the tree's state after every tick, handed to each monitor.

A RunMonitor is the run's tick view (btplan.acting.recorder.TickView): after every
tick it brings the TreeState up to date once and gives every monitor (the Groot2
server, the `.btlog` writer, the browser view) the same state and transitions. It
only reads what the run reports, so a watched run acts exactly like one that is not.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Protocol

from btplan.acting.records import TickRecord
from btplan.bt.node import Node
from btplan.bt.status import Status
from btplan.monitor.tree_state import TreeState

__all__ = ["Monitor", "RunMonitor"]


class Monitor(Protocol):
    """What watches a run: takes each tick's state, and ends with the run."""

    def publish(self, state: TreeState, transitions: list[tuple[int, int]]) -> None: ...

    def close(self) -> None: ...


class RunMonitor:
    """The tick view that feeds `monitors` (module docstring)."""

    def __init__(self, monitors: Sequence[Monitor], name: str = "MainTree",
                 facts: Iterable[str] = ()) -> None:
        self.monitors = list(monitors)
        self.state = TreeState(name, facts)

    def __call__(self, root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
        transitions = self.state.update(root, reached, record)
        for monitor in self.monitors:
            monitor.publish(self.state, transitions)

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
