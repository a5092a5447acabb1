"""What happened on each tick of a run, as one record and one JSON line per tick.

A run is judged by its trace, not by its outcome alone: the tests of the paper's four
reactive properties read which actions ran, which were halted, when the tree grew
and what the agents did. The same records feed `--trace FILE.jsonl`, the live view
and the final summary, so all three tell the same story.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Sequence
from typing import Any

from btplan.bt.trace import NodeTick
from btplan.records import field, record
from btplan.worlds.agents import Disturbance


@record(frozen=True, slots=True)
class ExpansionNote:
    """One expansion of the tree (Algorithm 1, lines 9-12), in words a reader can check."""

    condition: str
    achievers: tuple[str, ...]
    conflicts_resolved: int
    moves: int

    def to_dict(self) -> dict[str, Any]:
        return {"condition": self.condition, "achievers": list(self.achievers),
                "conflicts_resolved": self.conflicts_resolved, "moves": self.moves}


@record(frozen=True, slots=True)
class TickRecord:
    """One tick: the agents' disturbances before it, the tree's tick, the world's answer.

    `nodes` are the nodes the tick reached with their status (ids by depth-first
    position in the tree as it was ticked); the action lists hold grounded actions as
    text (`Pick(cube)`); `added`/`removed` are the facts that changed since the
    previous tick, whoever changed them.
    """

    tick: int
    status: str
    nodes: tuple[NodeTick, ...] = ()
    started: tuple[str, ...] = ()
    halted: tuple[str, ...] = ()
    finished: tuple[str, ...] = ()
    failed: tuple[str, ...] = ()
    disturbances: tuple[Disturbance, ...] = ()
    expansions: tuple[ExpansionNote, ...] = ()
    added: tuple[str, ...] = ()
    removed: tuple[str, ...] = ()
    planning_seconds: float = 0.0
    """CPU time spent expanding the tree in this tick (not written to traces: it varies)."""
    checks: int = 0
    """Conditions the tree checked in this tick (every tick of the tree, if it grew), and
    those looked at ahead of the running actions (btplan.acting.watch)."""

    def to_dict(self) -> dict[str, Any]:
        return {
            "tick": self.tick,
            "status": self.status,
            "nodes": [{"id": n.id, "kind": n.kind, "name": n.name, "status": n.status.value}
                      for n in self.nodes],
            "started": list(self.started),
            "halted": list(self.halted),
            "finished": list(self.finished),
            "failed": list(self.failed),
            "disturbances": [{"agent": d.agent, "kind": d.kind, "description": d.description}
                             for d in self.disturbances],
            "expansions": [e.to_dict() for e in self.expansions],
            "facts": {"added": list(self.added), "removed": list(self.removed)},
        }

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), separators=(",", ":"), ensure_ascii=False)


def records_to_jsonl(records: Iterable[TickRecord]) -> str:
    """The `--trace` file: one JSON object per tick, in tick order."""
    return "".join(r.to_json() + "\n" for r in records)


@record(slots=True)
class RunSummary:
    """Totals over a run's records, for the final summary and for assertions in tests."""

    ticks: int = 0
    started: list[str] = field(default_factory=list)
    finished: list[str] = field(default_factory=list)
    halted: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    disturbances: list[Disturbance] = field(default_factory=list)
    expansions: list[tuple[int, ExpansionNote]] = field(default_factory=list)

    @property
    def conflicts_resolved(self) -> int:
        return sum(e.conflicts_resolved for _, e in self.expansions)


def summarize(records: Sequence[TickRecord]) -> RunSummary:
    """Add up what the ticks did; expansions keep the tick at which they happened."""
    total = RunSummary(ticks=len(records))
    for r in records:
        total.started.extend(r.started)
        total.finished.extend(r.finished)
        total.halted.extend(r.halted)
        total.failed.extend(r.failed)
        total.disturbances.extend(r.disturbances)
        total.expansions.extend((r.tick, e) for e in r.expansions)
    return total
