"""The tree's last-resort search where the world supplies the trajectories and poses.

The task's groundings have no MoveTo in the simulator (no trajectory is an object of
the problem), and MoveTo's `not near(_)` is a wildcard delete the search's packed
states cannot hold: a condition stuck there stayed stuck. The search now grounds with
what the world refines and writes such deletes out; and the plan's steps are guarded by
a regression that splits `not blocks(_, t)` where a step puts one cube aside, or the
plan's first steps would wait for a path it is about to clear.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from btplan.acting import load
from btplan.acting.departures.refined_search import RefinedSearch, refines_for
from btplan.acting.loop import BlendedLoop
from btplan.model import ActionTemplate, Atom, GroundAction, GroundLiteral, Parameter
from btplan.planner.expand import literal_of
from btplan.planner.rescue import regress
from btplan.classical.search import SubgoalSearch, spell_out
from btplan.worlds.symbolic import SymbolicWorld
from tests.run.test_refined_baselines import Refiner

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
TASK = load(str(DOMAINS / "youbot.bt"))


def test_wildcard_deletes_are_written_out_over_the_atoms_named() -> None:
    drive = GroundAction(name="Go", args=("b",), add=(Atom("at", ("b",)),),
                         delete_patterns=(Atom("at", ("_",)),))
    spelled = spell_out([drive], [Atom("at", ("a",)), Atom("at", ("c",)), Atom("other", ("a",))])
    assert spelled[0].delete_patterns == ()
    assert set(spelled[0].delete) == {Atom("at", ("a",)), Atom("at", ("c",))}  # not at(b): added
    start = frozenset({Atom("at", ("a",))})
    assert spelled[0].apply(start) == drive.apply(start)


def test_the_search_plans_moves_only_with_their_deletes_written_out() -> None:
    go = [GroundAction(name="Go", args=(x,), add=(Atom("at", (x,)),),
                       delete_patterns=(Atom("at", ("_",)),)) for x in "ab"]
    fetch = GroundAction(name="Fetch", args=(), preconditions=(GroundLiteral(Atom("at", ("b",))),),
                         add=(Atom("got", ()),))
    start = frozenset({Atom("at", ("a",))})
    goal = [GroundLiteral(Atom("got", ())), GroundLiteral(Atom("at", ("a",)))]
    assert SubgoalSearch([*go, fetch]).search(start, goal) is None  # the moves are left out
    plan = SubgoalSearch(spell_out([*go, fetch], start)).search(start, goal)
    assert [str(a) for a in plan or []] == ["Go(b)", "Fetch()", "Go(a)"]


def test_a_stuck_condition_is_planned_with_the_worlds_paths_and_aside_spots() -> None:
    world = Refiner({Atom("hand_empty", ()), Atom("near", ("green",)),
                     Atom("blocks", ("blue", "to_goal"))})
    assert refines_for(TASK, world) and not refines_for(TASK, object())
    engine = RefinedSearch(TASK, world)
    state = engine.observe(world.facts())
    assert ("blocks", ("_", "to_goal")) in world.checked  # the paths measured before planning
    plan = engine.search(state, [GroundLiteral(Atom("on", ("green", "goal")))])
    assert plan is not None
    names = [str(a) for a in plan]
    assert names.index("Place(blue, aside_blue)") < names.index("MoveTo(goal, to_goal)")
    assert names[-1] == "Place(green, goal)"
    moves = [a for a in plan if a.name == "MoveTo"]
    assert all(a.delete_patterns == (Atom("near", ("_",)),) for a in moves)  # as the tree runs them
    state_now = state
    for step in plan:  # the plan runs in the task's own semantics, wildcard deletes and all
        assert step.applicable(state_now), step
        state_now = step.apply(state_now)


class RefiningWorld(SymbolicWorld):
    """The symbolic world with the simulator's way of naming values: a trajectory per
    location and an aside pose per cube, none of them an object of the task."""

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        if parameter.type == "trajectory":
            return [f"to_{binding['l']}"]
        return [f"aside_{binding['c']}"]


def test_the_loop_plans_a_stuck_condition_with_the_worlds_values_and_reaches_the_goal() -> None:
    world = RefiningWorld(TASK, seed=0)
    world.set_fact(Atom("blocks", ("blue", "to_goal")))
    loop = BlendedLoop(TASK, world)
    goal = loop.tree.root
    assert literal_of(goal) == GroundLiteral(Atom("on", ("green", "goal")))
    # The task's own groundings have no trajectory, so no MoveTo: nothing to plan with.
    assert loop.index.subgoal_search.search(world.facts(), [literal_of(goal)]) is None
    searched = loop.hooks.when_stuck(goal)  # the last-resort search, as the loop asks it
    assert searched is not None and loop.searches == 1
    assert "Place(blue, aside_blue)" in searched.achievers
    result = loop.run(200)
    assert result.reached, result.reason
    assert not result.expansions  # the searched plan did it all, in the tree
    done = [str(a) for a in world.executed]
    assert done.index("Place(blue, aside_blue)") < done.index("MoveTo(goal, to_goal)")


def test_regression_through_putting_one_cube_aside_keeps_the_other_cubes_off_the_path() -> None:
    place = TASK.instantiate(TASK.domain.action_map["Place"], ("blue", "aside_blue"))
    clear = GroundLiteral(Atom("blocks", ("_", "to_goal")), False)
    (before,) = regress([clear], [place], TASK)
    others = {GroundLiteral(Atom("blocks", (c, "to_goal")), False) for c in ("green", "red", "yellow")}
    assert others <= set(before) and clear not in before
    assert GroundLiteral(Atom("blocks", ("blue", "to_goal")), False) not in before
    assert clear in regress([clear], [place])[0]  # without the task: the whole wildcard
    # A wildcard over trajectories is not split: the world refines values of that type.
    anywhere = GroundLiteral(Atom("blocks", ("green", "_")), False)
    assert regress([anywhere], [place], TASK)[0][-1] == anywhere
