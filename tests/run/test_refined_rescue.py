"""The tree's last-resort search where the world supplies the trajectories and poses.

The task's groundings have no MoveTo in the simulator (no trajectory is an object of
the problem), and MoveTo's `not near(_)` is a wildcard delete the search's packed
states cannot hold: a condition stuck there stayed stuck. The search now grounds with
what the world refines and writes such deletes out.
"""

from __future__ import annotations

from pathlib import Path

from btplan.acting import load
from btplan.acting.refined_search import RefinedSearch, refines_for
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.search import SubgoalSearch, spell_out
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
