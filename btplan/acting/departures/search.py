"""Plans found by search, put into the tree: the last resort when backchaining is stuck.

btplan/planner/rescue.py says what is searched for and where the plan goes; here the
plan's actions are grounded for the loop, and the checks the plan brings are never
expanded. Either way the tree only grows. The `search_stuck` option of the planner.
"""

from __future__ import annotations

from btplan.acting.hooks import Departure
from btplan.acting.state import Expansion, LoopState
from btplan.bt import Node
from btplan.model import GroundAction

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.planner.rescue import Rescuer


class LastResortSearch(Departure):
    """Plans a stuck condition by a complete search; keeps the search engine it made."""

    name = "search_stuck"

    def __init__(self) -> None:
        self.rescuer: Rescuer | None = None

    def when_stuck(self, node: Node) -> Expansion | None:
        """Plan the stuck condition `node` by search, or None."""
        loop = self.loop
        rescuer = self._rescuer()
        if rescuer is None:
            return None
        from btplan.acting.departures.refined_search import RefinedSearch

        state = loop.world.facts()
        if isinstance(rescuer.engine, RefinedSearch):  # the world's values, measured now
            state = rescuer.engine.observe(state)
        rescued = rescuer.rescue(loop.tree, node, state, loop.deadline)
        if rescued is None:
            return None
        literal, steps, checks = rescued
        loop.adopt(steps, [*checks, node])
        return loop.record(literal, steps, 0, 0)

    def _rescuer(self) -> Rescuer | None:
        """The search engine, made when something is first stuck: over the world's
        refined values in a world that refines them, the task's groundings otherwise
        (None: the groundings are too many to search, AchieverIndex.fits_search)."""
        if self.rescuer is None:
            from btplan.acting.departures.refined_search import RefinedSearch, refines_for
            from btplan.planner.rescue import Rescuer

            loop = self.loop
            options, index = loop.options, loop.index
            mutexes = index.mutexes if options.mutexes else None
            refined = refines_for(loop.task, loop.world)
            if not refined and not index.fits_search():
                return None
            engine = RefinedSearch(loop.task, loop.world) if refined else index.subgoal_search
            self.rescuer = Rescuer(loop.task, engine, mutexes)
        return self.rescuer


def adopt_plan(loop: LoopState, steps: list[GroundAction]) -> None:
    """Put a plan for the whole goal behind the goal tree (`plan_whole_goal`)."""
    from btplan.planner.rescue import plan_whole_goal

    loop.adopt(steps, plan_whole_goal(loop.tree, loop.task, steps))
