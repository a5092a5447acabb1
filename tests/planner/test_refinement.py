"""RefineActions again: a grounding whose refined value went stale is refined anew.

A trajectory is the world's value for MoveTo's refined parameter. When the world
changes so that the value no longer meets the template's `where` constraints (the
route is gone), the grounded action must not run on a world that no longer exists:
it fails, and the failed condition gets the values the world offers now.
"""

from __future__ import annotations

from pathlib import Path

from btplan.acting.loop import BlendedLoop
from btplan.lang import load
from btplan.model import Atom
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS


def detour_task(tmp_path: Path) -> SymbolicWorld:
    text = (DOMAINS / "pick_place_obstacle.bt").read_text(encoding="utf-8")
    text = text.replace("tau_aside : trajectory", "tau_aside, tau_detour : trajectory")
    path = tmp_path / "detour.bt"
    path.write_text(text, encoding="utf-8")
    return SymbolicWorld(load([str(path)]))


def test_a_route_that_is_gone_is_refined_again_instead_of_driven(tmp_path: Path) -> None:
    world = detour_task(tmp_path)
    loop = BlendedLoop(world.task, world)
    changed: list[int] = []

    def hook(tick: int) -> None:
        if not changed and Atom("holding", ("cube",)) in world.facts():
            changed.append(tick)  # the way to the goal is now another one
            world.clear_fact(Atom("route", ("goal", "tau_goal")))
            world.set_fact(Atom("route", ("goal", "tau_detour")))

    result = loop.run(100, before_tick=hook)
    assert result.reached and changed
    executed = [str(a) for a in world.executed]
    assert "MoveTo(goal, tau_goal)" not in executed
    assert executed[-2:] == ["MoveTo(goal, tau_detour)", "Place(cube, goal)"]
    # The stale grounding stays in the tree (it only grows) but never runs: it fails
    # where it starts, and the fallback goes on to the refined one.
    assert {str(a) for a in world.failed} == {"MoveTo(goal, tau_goal)"}
    assert [e.condition for e in loop.expansions].count("near(goal)") == 2


def test_the_symbolic_world_keeps_the_goal_for_the_goal(tmp_path: Path) -> None:
    world = detour_task(tmp_path)
    place = world.task.domain.action_map["Place"]
    (target,) = [p for p in place.parameters if p.refined]
    assert world.refine(place, {"o": "sphere"}, target) == ["aside"]
