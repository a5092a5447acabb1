"""When the loop cannot grow the tree any further, plan offline from the state of now.

Acting online, the loop makes one attempt: a condition without an achiever that fits,
or without a conflict-free place, ends it (the Sussman anomaly does, from the initial
state). Offline planning (btplan.acting.offline) tries other strategies, gives up the
achiever choices the failure is blamed on, and searches for the whole goal as a last
resort. So before the run gives up, the task is planned offline from the facts the
world reports now, and the loop acts on that tree instead, growing it as before where
the world departs from it. Once per run (`ActingConfig.plan_offline_when_stuck`), and
not in a world whose actions refine values as they run: offline planning simulates the
actions symbolically.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from btplan.acting.loop import BlendedLoop
from btplan.acting.state import TickReport
from btplan.bt import FAILURE
from btplan.errors import BtplanError
from btplan.model import Atom, Literal, Task
from btplan.records import replace

__all__ = ["OfflineFallback"]

TIMEOUT = 60.0
"""Seconds offline planning may take when the loop is stuck (a stop request ends it sooner)."""


class OfflineFallback:
    """Plans offline once, when the loop is stuck, and hands the tree to the loop."""

    def __init__(self, task: Task, stop: Callable[[], bool] | None = None) -> None:
        self.task = task
        self.stop = stop
        self.used = False

    def take_over(self, loop: BlendedLoop) -> TickReport | None:
        """The tick's report with the offline plan's expansions once the loop acts on its
        tree; None when it was used already or finds no tree either."""
        if self.used:
            return None
        self.used = True
        from btplan.acting.offline import plan

        started = time.process_time()
        try:
            planned = plan(self.at(loop.world.facts()), timeout=TIMEOUT, stop=self.stop)
        except BtplanError:
            return None
        if planned.memory is None:
            return None
        loop.resume(planned.tree, planned.memory)
        report = TickReport(loop.ticks, FAILURE, list(planned.expansions))
        report.add_planning(time.process_time() - started)
        return report

    def at(self, facts: frozenset[Atom]) -> Task:
        """The task with the facts of now as its initial state."""
        init = tuple(sorted((Literal(predicate=a.predicate, args=a.args) for a in facts),
                            key=str))
        return Task(domain=self.task.domain, problem=replace(self.task.problem, init=init))
