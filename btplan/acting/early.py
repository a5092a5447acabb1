"""Expansions made before a tick reaches the condition, in the tick the loop is in.

The loop keeps a queue of such conditions (`EarlyExpansions`); departures fill it: the
look-ahead with the later false preconditions of an action whose first false one was
just expanded, and with the conditions ahead of the running actions that an outside
change broke (btplan.acting.departures.later, .watch); credit for other goals with
the step another goal needs (btplan.acting.departures.other_goals). Each is expanded
as the tick that reached it would expand it, conflict resolution included, and after
each the deeper look (btplan.acting.departures.ahead) expands the preconditions of its
new achiever that would make the robot give up what it holds. One without achievers
or without a conflict-free place now is left for that tick to find. Off in the
published algorithm: nothing fills the queue.
"""

from __future__ import annotations

import time

from btplan.acting.departures.ahead import deeper_false, forced_out, later_false
from btplan.acting.departures.prepare import RelaxedPlans, on_the_way, relaxed_plans
from btplan.acting.departures.watch import broken_ahead
from btplan.acting.state import LoopState, TickReport
from btplan.bt import Node
from btplan.model import Atom, GroundLiteral
from btplan.planner import literal_of

__all__ = ["EarlyExpansions"]


class EarlyExpansions:
    """The loop's queue of conditions to expand early in this tick, and how it expands them."""

    def __init__(self, loop: LoopState) -> None:
        self.loop = loop
        self.queue: list[Node] = []
        self._plans: RelaxedPlans | None = None

    # --- filled by the departures ----------------------------------------------------

    def replace(self, nodes: list[Node]) -> None:
        """These, instead of what waited (a new expansion's later preconditions)."""
        self.queue = list(nodes)

    def extend(self, nodes: list[Node]) -> None:
        """These after what already waits (conditions added for another goal's step)."""
        self.queue += nodes

    # --- run by the loop and the departures --------------------------------------------

    def run(self, report: TickReport) -> None:
        """Expand the queued conditions, as the tick would once the robot had achieved
        the one before; and those an expansion here adds. After each, the false
        preconditions of the achiever it got that conflict where they stand
        (`expand_forced`)."""
        state = self.loop.world.facts()
        while self.queue:
            node = self.queue.pop(0)
            if not self._room(report):
                self.queue = []
                return
            literal = literal_of(node)
            if literal is None or literal.holds(state):
                continue
            if self.loop.expand_now(report, node, state):
                self.expand_forced(report, node)

    def expand_forced(self, report: TickReport, node: Node) -> None:
        """Expand the false preconditions of `node`'s new achiever that every achiever of
        theirs would make the robot give up what an earlier condition holds
        (btplan.acting.departures.ahead): conflict resolution puts them in front now,
        rather than the tick finding them only with the cube in hand. The others wait.

        The facts are read again: the expansion may have refined a value (a trajectory)
        that the world measures only from now on."""
        loop = self.loop
        state = loop.world.facts()
        for deeper in deeper_false(node, state, loop.expanded):
            if not self._room(report):
                return
            literal = literal_of(deeper)
            assert literal is not None

            def reached_first(held: list[GroundLiteral], atom: Atom = literal.atom) -> bool:
                goals = [h.atom for h in held if h.positive]
                return on_the_way(self.plans(), state, goals, atom)

            achievers, spare = loop.achievers(deeper, literal, state)
            if forced_out(node, achievers, loop.judge(),
                          reached_first if literal.positive else None):
                loop.expand_now(report, deeper, state, (achievers, spare))

    def expand_if_forced(self, report: TickReport, nodes: list[Node]) -> None:
        """Of the later false preconditions `nodes`, expand those whose first achiever
        has a false precondition that every achiever of it would make the robot give up
        what is held before them: only then is the later condition's subtree needed
        before the tick reaches it. Each is looked at as `expand_forced` would, its
        precondition's achievers ranked where the later condition stands."""
        loop = self.loop
        for node in nodes:
            if not self._room(report):
                return
            literal = literal_of(node)
            state = loop.world.facts()
            if literal is None or literal.holds(state) or node in loop.expanded:
                continue
            found = loop.achievers(node, literal, state)
            if not found[0]:
                continue
            refined = loop.world.facts()  # the achiever may have refined a trajectory
            needs = [p for p in found[0][0].preconditions if not p.holds(refined)]
            if any(self._forces(node, need, refined) for need in needs):
                if loop.expand_now(report, node, state, found):
                    self.expand_forced(report, node)

    def expand_broken(self, report: TickReport, last: frozenset[Atom]) -> None:
        """Expand the conditions ahead of the running actions that held in `last`, the
        state after the previous tick, and an outside change made false; each with its
        later false preconditions. Looking is monitoring (`report.checks_ahead`); the
        expansions are planning, timed as such."""
        loop = self.loop
        state = loop.world.facts()
        broken, checks = broken_ahead(loop.tree.root, state, last, loop.expanded)
        report.looked_ahead(checks)
        if not broken:
            return
        started = time.process_time()
        try:
            for node in broken:
                if not self._room(report):
                    return
                ahead = later_false(node, state, loop.expanded)
                if loop.expand_now(report, node, state):
                    self.queue = ahead + self.queue
                    self.run(report)
        finally:
            report.add_planning(time.process_time() - started)

    def plans(self) -> RelaxedPlans:
        """The relaxed plans of the loop's relaxed model (kept while the loop lives)."""
        if self._plans is None:
            self._plans = relaxed_plans(self.loop.index.relaxed)
        return self._plans

    # ---------------------------------------------------------------------------------

    def _forces(self, node: Node, need: GroundLiteral, state: frozenset[Atom]) -> bool:
        """Whether every achiever of `need`, a precondition of `node`'s achiever, would
        make the robot give up what is held before `node` (`forced_out`)."""

        def reached_first(held: list[GroundLiteral]) -> bool:
            goals = [h.atom for h in held if h.positive]
            return on_the_way(self.plans(), state, goals, need.atom)

        achievers, _ = self.loop.achievers(node, need, state)
        return forced_out(node, achievers, self.loop.judge(),
                          reached_first if need.positive else None)

    def _room(self, report: TickReport) -> bool:
        """Whether this tick and the run may still expand."""
        options = self.loop.options
        return (len(report.expansions) < options.expansions_per_tick
                and len(self.loop.expansions) < options.max_expansions)

