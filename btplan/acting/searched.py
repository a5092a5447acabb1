"""Plans found by search, put into the tree: the last resort when backchaining is stuck.

btplan/planner/rescue.py says what is searched for and where the plan goes; here the
plan's actions are grounded for the loop, and the checks the plan brings are never
expanded. Either way the tree only grows.
"""

from __future__ import annotations

from btplan.acting.state import Expansion, LoopState
from btplan.bt import Node
from btplan.model import GroundAction


def search_stuck(loop: LoopState, node: Node) -> Expansion | None:
    """Plan a stuck condition by search (`search_stuck`), or None."""
    options, index = loop.options, loop.index
    if not options.search_stuck:
        return None
    from btplan.acting.refined_search import RefinedSearch, refines_for
    from btplan.planner.rescue import Rescuer  # imported only when something is stuck

    if loop.rescuer is None:
        mutexes = index.mutexes if options.mutexes else None
        engine = (RefinedSearch(loop.task, loop.world) if refines_for(loop.task, loop.world)
                  else index.subgoal_search)
        loop.rescuer = Rescuer(loop.task, engine, mutexes)
    state = loop.world.facts()
    if isinstance(loop.rescuer.engine, RefinedSearch):  # the world's values, measured now
        state = loop.rescuer.engine.observe(state)
    rescued = loop.rescuer.rescue(loop.tree, node, state, loop.deadline)
    if rescued is None:
        return None
    literal, steps, checks = rescued
    _adopt(loop, steps, [*checks, node])
    return loop.record(literal, steps, 0, 0)


def adopt_plan(loop: LoopState, steps: list[GroundAction]) -> None:
    """Put a plan for the whole goal behind the goal tree (`plan_whole_goal`)."""
    from btplan.planner.rescue import plan_whole_goal

    _adopt(loop, steps, plan_whole_goal(loop.tree, loop.task, steps))


def _adopt(loop: LoopState, steps: list[GroundAction], checks: list[Node]) -> None:
    for action in steps:
        loop.grounding[action.key] = action
    loop.expanded.update(checks)
    loop.dead.update(checks)
    loop.searches += 1
