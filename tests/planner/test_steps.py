"""The planner steps as plain functions: achievers, BFS choice, mutexes, moves."""

from __future__ import annotations

from btplan.bt import Action, BehaviorTree, Condition, Fallback, Sequence
from btplan.bt.decorators import Inverter
from btplan.bt.status import FAILURE
from btplan.lang import load
from btplan.model import Atom, GroundLiteral
from btplan.planner import (
    AchieverIndex,
    Judge,
    Mutexes,
    PlannerOptions,
    find_conflicts,
    get_condition_to_expand,
    increase_priority,
)
from btplan.planner.achievers import guards
from btplan.planner.expand import condition_node, expand_tree, initial_tree
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS, shape


def lit(text: str, positive: bool = True) -> GroundLiteral:
    name, _, rest = text.partition("(")
    args = tuple(a.strip() for a in rest.rstrip(")").split(",") if a.strip())
    return GroundLiteral(Atom(name, args), positive)


def obstacle() -> tuple[AchieverIndex, SymbolicWorld]:
    task = load([str(DOMAINS / "pick_place_obstacle.bt")])
    return AchieverIndex(task), SymbolicWorld(task)


def test_achievers_unify_bind_refine_and_skip_where_literals() -> None:
    index, world = obstacle()
    state = world.facts()
    moves = index.achievers(lit("near(cube)"), state, world.refine)
    assert [str(a) for a in moves] == ["MoveTo(cube, tau_cube)"]  # t refined by route(l, t)
    assert [str(p) for p in moves[0].preconditions] == ["not blocks(_, tau_cube)"]
    # Place's refined target comes from the world, which keeps the goal for the goal's
    # own objects: an object to put down goes aside.
    assert [str(a) for a in index.achievers(lit("hand_empty()"), state, world.refine)] == [
        "Drop(cube)", "Drop(sphere)", "Place(cube, aside)", "Place(sphere, aside)"]
    # The path is free: nothing to undo.
    free = lit("blocks(_, tau_goal)", positive=False)
    assert free.holds(state) and index.achievers(free, state, world.refine) == []
    world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
    assert not free.holds(world.facts())
    found = index.achievers(free, world.facts(), world.refine)
    assert [str(a) for a in found] == ["Place(sphere, aside)"]
    # Its alternative is guarded by the instance it undoes.
    assert guards(found[0], free, world.facts()) == (lit("blocks(sphere, tau_goal)"),)


def test_a_wildcard_condition_with_two_instances_undoes_each() -> None:
    index, world = obstacle()
    world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
    world.set_fact(Atom("blocks", ("cube", "tau_goal")))
    free = lit("blocks(_, tau_goal)", positive=False)
    found = index.achievers(free, world.facts(), world.refine)
    assert sorted(str(a) for a in found) == ["Place(cube, aside)", "Place(sphere, aside)"]
    assert [guards(a, free, world.facts()) for a in found if a.args[0] == "cube"] == [
        (lit("blocks(cube, tau_goal)"),)]
    assert world.check(("blocks", ("_", "tau_goal")))
    assert not world.check(("blocks", ("_", "tau_cube")))


def test_negative_conditions_are_achieved_by_deleting_actions_including_wildcards() -> None:
    index, world = obstacle()
    world.set_fact(Atom("near", ("cube",)))
    found = index.achievers(lit("near(cube)", positive=False), world.facts(), world.refine)
    assert found and all(a.name == "MoveTo" for a in found)
    assert "MoveTo(cube, tau_cube)" not in [str(a) for a in found]  # it would re-add near(cube)
    assert isinstance(condition_node(lit("near(cube)", False), index.task), Inverter)


def test_achievers_are_ranked_cheapest_first_and_bounded() -> None:
    task = load([str(DOMAINS / "planner_sussman.bt")])
    world = SymbolicWorld(task)
    found = AchieverIndex(task, PlannerOptions(max_alternatives=2)).achievers(
        lit("holding(a)"), world.facts(), world.refine)
    assert len(found) == 2 and str(found[0]) == "pickup(a)"


def test_condition_to_expand_is_the_first_failed_one_breadth_first() -> None:
    near, hand = Condition("near", ("cube",)), Condition("hand_empty")
    deep = Condition("free", ("t",))
    tree = BehaviorTree(Sequence([Fallback([near, Sequence([deep, Action("Go")])]), hand]))
    for node in (near, hand, deep):
        node.status = FAILURE
    assert get_condition_to_expand(tree, set()) is hand  # depth 1, though rightmost
    assert get_condition_to_expand(tree, {hand}) is near  # depth 2
    assert get_condition_to_expand(tree, {near, hand}) is deep  # depth 3
    assert get_condition_to_expand(tree, {near, hand, deep}) is None


def test_h2_mutexes_see_what_cannot_hold_together() -> None:
    index, _ = obstacle()
    mutexes: Mutexes = index.mutexes
    assert mutexes.exclusive(lit("holding(cube)"), lit("hand_empty()"))
    assert mutexes.exclusive(lit("holding(cube)"), lit("holding(sphere)"))
    assert not mutexes.exclusive(lit("holding(cube)"), lit("near(goal)"))
    assert mutexes.exclusive(lit("near(cube)"), lit("near(cube)", positive=False))


def test_increase_priority_climbs_to_the_nearest_sequence_and_leaves_a_copy() -> None:
    task = load([str(DOMAINS / "pick_place.bt")])
    tree = initial_tree(task)
    index = AchieverIndex(task)
    world = SymbolicWorld(task)
    goal = tree.root
    place = expand_tree(tree, goal, index.achievers(lit("on(cube, goal)"), world.facts(),
                                                    world.refine), task)
    near_goal = place.children[1].children[1]
    move = expand_tree(tree, near_goal, index.achievers(lit("near(goal)"), world.facts(),
                                                        world.refine), task)
    free = move.children[1].children[0]
    assert increase_priority(tree, free)  # leftmost in MoveTo's sequence: before its parent,
    # which is a Fallback, so up to the Place sequence, just before the near(goal) subtree
    assert shape(tree.root) == ("?", "on(cube, goal)", (
        "->", "holding(cube)", "free(tau_goal)",
        ("?", "near(goal)", ("->", "free(tau_goal)", "[MoveTo(goal, tau_goal)]")),
        "[Place(cube, goal)]"))
    assert increase_priority(tree, free)
    assert shape(tree.root)[2][1] == "free(tau_goal)"
    assert not increase_priority(tree, free)  # nowhere earlier in a Sequence


def test_an_earlier_condition_that_excludes_a_need_is_a_conflict() -> None:
    index, world = obstacle()
    task = index.task
    hold = Fallback([Condition("holding", ("cube",)),
                     Sequence([Condition("hand_empty"), Action("Pick", ("cube",))])])
    world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
    free_lit = lit("blocks(_, tau_goal)", positive=False)
    clear = index.achievers(free_lit, world.facts(), world.refine)
    free = condition_node(free_lit, task)
    root = Sequence([hold, free])
    tree = BehaviorTree(root)
    subtree = expand_tree(tree, free, clear, task)
    grounding = {a.key: a for a in clear}
    grounding[("Pick", ("cube",))] = world.ground(("Pick", ("cube",)))
    found = find_conflicts(subtree, Judge(grounding, index.mutexes))
    # Putting the sphere aside needs it in hand, which holding the cube excludes.
    assert [str(c) for c in found] == [
        "holding(cube) excludes holding(sphere) (needed after it holds)"]
    assert find_conflicts(hold, Judge(grounding, index.mutexes)) == []
