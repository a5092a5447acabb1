"""Turning what happened around one tick into a TickRecord, and nothing more.

The recorder watches: the agents act through it before a tick, the tree's tick
recorder tells which nodes the tick reached, the loop's skills tell what started,
finished, was halted or failed, and the facts before and after tell what changed.
Records go to the view (the live tree, the trace file) as they are made; the summary
adds them up, and the last few are kept for the outcome.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, MutableSequence, Sequence
from typing import Any

from btplan.acting.loop import BlendedLoop, TickReport
from btplan.acting.records import ExpansionNote, RunSummary, TickRecord
from btplan.acting.state import Expansion
from btplan.bt import FAILURE, Node, Status
from btplan.bt.trace import TickRecorder
from btplan.model import Atom
from btplan.worlds.agents import Agent, Disturbance, act_all

__all__ = ["Recorder", "TickView", "note"]

TickView = Callable[[Node, Mapping[int, Status], TickRecord], None]
"""Called after every tick with the tree, id(node) -> status for the nodes this tick
reached, and the tick's record: the live view and the trace file are such views."""


class Recorder:
    """Records each tick of `loop` acting in `world` with `agents` (module docstring)."""

    def __init__(self, loop: BlendedLoop, world: Any, agents: Sequence[Agent],
                 view: TickView | None, kept: MutableSequence[TickRecord]) -> None:
        self.loop, self.world, self.agents, self.view = loop, world, list(agents), view
        self.kept = kept
        self.summary = RunSummary()
        self.tree_recorder = TickRecorder()
        self.tree_recorder.attach(loop.tree)
        self._facts: frozenset[Atom] = loop.skills.facts()
        self._disturbances: list[Disturbance] = []
        self._last_tick = 0
        self.goal_held = False
        """Whether the goal held after the last tick recorded."""

    def before(self, tick: int) -> None:
        """Let the agents act before `tick`."""
        self._disturbances = act_all(self.agents, self.world, tick)

    def after(self, report: TickReport, goal: str = "", held: bool | None = None) -> None:
        """Record the tick the loop just made (`goal`: "reached" or "lost" on a change;
        `held`: whether the goal holds after it)."""
        if held is not None:
            self.goal_held = held
        traces = list(self.tree_recorder.traces)
        self.tree_recorder.traces.clear()
        nodes = traces[-1].nodes if traces else ()
        # The ids are those of the last tick recorded: the tree may have been planned
        # anew or grown before it, within this tick.
        ids = {f"n{i}": node for i, node in enumerate(self.tree_recorder.last_nodes)}
        reached = {id(ids[n.id]): n.status for n in nodes if n.id in ids}
        events = self.loop.skills.take_events()
        facts = self.loop.skills.facts()
        finished = (*events.finished,)
        record = TickRecord(
            tick=report.tick,
            status=report.status.value,
            nodes=nodes,
            started=tuple(str(a) for a in events.started),
            halted=tuple(str(a) for a in events.halted),
            finished=tuple(str(a) for a in finished),
            failed=tuple(str(a) for a in events.failed),
            disturbances=tuple(self._disturbances),
            expansions=tuple(note(e) for e in report.expansions),
            added=tuple(str(a) for a in sorted(facts - self._facts)),
            removed=tuple(str(a) for a in sorted(self._facts - facts)),
            observed=tuple(str(a) for a in events.observed),
            errors=tuple(events.errors),
            goal=goal,
            planning_seconds=report.planning_seconds,
            checks=sum(1 for t in traces for n in t.nodes if n.kind == "Condition")
            + report.checks_ahead,
            plan_lines=tuple(a.ipc() for a in finished),
        )
        self._facts = facts
        self._disturbances = []
        self._last_tick = report.tick
        self.summary.add(record)
        self.kept.append(record)
        if self.view is not None:
            self.view(self.loop.tree.root, reached, record)

    def close_tick(self) -> None:
        """The loop stopped inside a tick (a planning error): record that tick as failed."""
        if self._last_tick != self.loop.ticks:
            self.after(TickReport(self.loop.ticks, FAILURE))

    def detach(self) -> None:
        """Stop recording the loop's tree, on every way out of a run: its nodes get their
        plain classes back, so the tree handed to the caller ticks without tracing."""
        self.tree_recorder.detach(self.loop.tree)


def note(expansion: Expansion) -> ExpansionNote:
    """An expansion as the trace shows it: the condition, its achievers, the moves made."""
    return ExpansionNote(
        condition=str(expansion.condition),
        achievers=tuple(str(a) for a in expansion.achievers),
        conflicts_resolved=int(expansion.conflicts_resolved),
        moves=int(expansion.moves),
    )
