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
        """The expansion as the trace writes it."""
        return {"condition": self.condition, "achievers": list(self.achievers),
                "conflicts_resolved": self.conflicts_resolved, "moves": self.moves}


@record(frozen=True, slots=True)
class TickRecord:
    """One tick: the agents' disturbances before it, the tree's tick, the world's answer.

    `nodes` are the nodes the tick reached with their status (ids by depth-first
    position in the tree as it was ticked); the action lists hold grounded actions as
    text (`Pick(cube)`); `added`/`removed` are the facts that changed since the
    previous tick, whoever changed them. `finished` includes `observed`: actions whose
    effects all held when the tree turned away from them, before they reported SUCCESS.
    `goal` is "reached" on the tick the goal came to hold and "lost" on the tick it
    stopped holding (a run that keeps going after the goal, `keep=True`).
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
    observed: tuple[str, ...] = ()
    errors: tuple[tuple[str, str], ...] = ()
    """(action or condition, message) of every exception the world raised in this tick."""
    goal: str = ""
    planning_seconds: float = 0.0
    """CPU time spent expanding the tree in this tick (not written to traces: it varies)."""
    checks: int = 0
    """Conditions the tree checked in this tick (every tick of the tree, if it grew), and
    those looked at ahead of the running actions (btplan.acting.departures.watch)."""
    plan_lines: tuple[str, ...] = ()
    """The finished actions in the IPC plan format (for `--plan-out`; not in the trace)."""

    def to_dict(self) -> dict[str, Any]:
        """The tick as the trace writes it (docs/cli.md, "The trace")."""
        out = {
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
        # Written only when they happen, so that the traces of plain runs stay as they were.
        if self.observed:
            out["observed"] = list(self.observed)
        if self.errors:
            out["errors"] = [{"action": what, "message": why} for what, why in self.errors]
        if self.goal:
            out["goal"] = self.goal
        return out

    def to_json(self) -> str:
        """The tick as one line of JSON."""
        return json.dumps(self.to_dict(), separators=(",", ":"), ensure_ascii=False)


def records_to_jsonl(records: Iterable[TickRecord]) -> str:
    """The `--trace` file: one JSON object per tick, in tick order."""
    return "".join(r.to_json() + "\n" for r in records)


LISTED = 10_000
"""Entries a summary list keeps; past that it only counts, so a run of a million ticks
takes no more memory than one of ten thousand (the trace has every tick)."""


@record(slots=True)
class RunSummary:
    """Totals over a run's ticks, for the final summary and for assertions in tests.

    Built tick by tick (`add`): each list keeps its first LISTED entries and `counts`
    has every total, so memory stays flat however long the run."""

    ticks: int = 0
    started: list[str] = field(default_factory=list)
    finished: list[str] = field(default_factory=list)
    observed: list[str] = field(default_factory=list)
    halted: list[str] = field(default_factory=list)
    failed: list[str] = field(default_factory=list)
    errors: list[tuple[str, str]] = field(default_factory=list)
    disturbances: list[Disturbance] = field(default_factory=list)
    expansions: list[tuple[int, ExpansionNote]] = field(default_factory=list)
    goal_reached: list[int] = field(default_factory=list)
    """Ticks on which the goal came to hold."""
    goal_lost: list[int] = field(default_factory=list)
    """Ticks on which the goal stopped holding after it held."""
    counts: dict[str, int] = field(default_factory=dict)
    planning_seconds: float = 0.0
    checks: int = 0
    overruns: int = 0
    """Ticks that started late because the one before took longer than the period."""
    worst_lateness: float = 0.0
    """Seconds the latest tick started after its time."""
    unstopped: list[str] = field(default_factory=list)
    """Skills that did not report stopping within the wait after the run halted them."""

    @property
    def conflicts_resolved(self) -> int:
        """Conflicts resolved over every expansion of the run."""
        return sum(e.conflicts_resolved for _, e in self.expansions)

    def end(self, unstopped: list[str], overruns: int, worst_lateness: float) -> None:
        """How the run ended: the skills that did not stop, and how its pacing went."""
        self.unstopped.extend(unstopped)
        self.overruns, self.worst_lateness = overruns, worst_lateness

    def count(self, name: str) -> int:
        """How many there were in all (`started`, `finished`, ...), listed or not."""
        return self.counts.get(name, 0)

    def add(self, r: TickRecord) -> None:
        """Add one tick."""
        self.ticks += 1
        self.planning_seconds += r.planning_seconds
        self.checks += r.checks
        for name, items in (("started", r.started), ("finished", r.finished),
                            ("observed", r.observed), ("halted", r.halted),
                            ("failed", r.failed), ("errors", r.errors),
                            ("disturbances", r.disturbances)):
            if items:
                self._extend(name, items)
        if r.expansions:
            self._extend("expansions", [(r.tick, e) for e in r.expansions])
        if r.goal == "reached":
            self._extend("goal_reached", (r.tick,))
        elif r.goal == "lost":
            self._extend("goal_lost", (r.tick,))

    def _extend(self, name: str, items: Sequence[Any]) -> None:
        self.counts[name] = self.counts.get(name, 0) + len(items)
        kept: list[Any] = getattr(self, name)
        room = LISTED - len(kept)
        if room > 0:
            kept.extend(items[:room])


def summarize(records: Iterable[TickRecord]) -> RunSummary:
    """Add up what the ticks did; expansions keep the tick at which they happened."""
    total = RunSummary()
    for r in records:
        total.add(r)
    return total
