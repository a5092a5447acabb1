"""Offline planning inside a run: before the first action, and when the loop is stuck.

Acting online, the loop makes one attempt: a condition without an achiever that fits,
or without a conflict-free place, ends it (the Sussman anomaly does, from the initial
state). Offline planning (btplan.acting.offline) tries other strategies, gives up the
achiever choices the failure is blamed on, and searches for the whole goal as a last
resort. So before the run gives up, the task is planned offline from the facts the
world reports now, and the loop acts on that tree instead, growing it as before where
the world departs from it. Once per run (`ActingConfig.plan_offline_when_stuck`), and
not in a world whose actions refine values as they run: offline planning simulates the
actions symbolically.

The same planning before the first tick (`ActingConfig.plan_before_acting`) gives the
loop the tree `btplan plan` finds, its shorter plan first, so that an undisturbed run
executes that plan and no more; the loop grows that tree online where the world departs
from it. Planning that fails leaves the loop to grow its own tree; a stop request while
it plans ends the run before any action.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from btplan.acting.config import ActingConfig
from btplan.acting.loop import BlendedLoop
from btplan.acting.pacing import Stop
from btplan.acting.state import TickReport
from btplan.bt import FAILURE
from btplan.errors import BtplanError, Interrupted, PlanningError
from btplan.model import Atom, Literal, Task
from btplan.planner import PlannerOptions
from btplan.records import replace
from btplan.robot.contract import capabilities_of

__all__ = ["OfflineTurns"]

TIMEOUT = 60.0
"""Seconds offline planning may take when the loop is stuck (a stop request ends it sooner)."""

AHEAD_TIMEOUT = 10.0
"""Seconds planning before the first action may take; beyond them the loop grows its own
tree and the robot starts moving (a stop request ends it sooner)."""


class OfflineTurns:
    """Plans offline before acting, and once when the loop is stuck, and hands the tree
    to the loop; each turn only where the run's configuration and its world allow it."""

    def __init__(self, task: Task, config: ActingConfig, world: object,
                 stop: Callable[[], bool] | None = None) -> None:
        declared = capabilities_of(world)
        self.task = task
        self.stop = stop
        self.when_stuck = config.plan_offline_when_stuck and not declared.continuous
        self.before_acting = (config.plan_before_acting and not declared.continuous
                              and not declared.own_values)
        self.used = False
        self.options = config.planner

    def take_over(self, loop: BlendedLoop) -> TickReport | None:
        """The tick's report with the offline plan's expansions once the loop acts on its
        tree; None when it was used already, is not allowed, or finds no tree either."""
        if self.used or not self.when_stuck:
            return None
        self.used = True
        return self._plan(loop, TIMEOUT)

    def ahead(self, loop: BlendedLoop) -> TickReport | None:
        """Before the first tick: the loop acts on the tree planned offline from the facts
        of now; the report holds its expansions (None: planning found no tree, and the
        loop grows its own, or planning ahead is not allowed). Does not use up the turn
        for when the loop is stuck."""
        if not self.before_acting:
            return None
        return self._plan(loop, AHEAD_TIMEOUT, self.options)

    def _plan(self, loop: BlendedLoop, timeout: float,
              first: PlannerOptions | None = None) -> TickReport | None:
        """Plan from the facts of now and hand the tree to the loop: with `first`, the
        loop's own options are tried first (breadth-first expansion leaves the shallow
        alternatives in the tree, so that an undone action is redone without expanding),
        then `btplan plan`'s strategies within what is left of `timeout`."""
        from btplan.acting.offline import plan

        started, deadline = time.process_time(), time.perf_counter() + timeout
        task = self.at(loop.world.facts())
        try:
            try:
                planned = plan(task, timeout=timeout, stop=self.stop, options=first,
                               last_resort=first is None)
            except PlanningError:
                if first is None:
                    raise
                left = deadline - time.perf_counter()
                if left <= 0:
                    return None
                planned = plan(task, timeout=left, stop=self.stop)
        except Interrupted:  # the caller asked the run to stop while it planned
            raise Stop from None
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
