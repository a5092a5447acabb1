"""The paper's Examples 1 and 2: tree structure after each expansion, and execution."""

from __future__ import annotations

from btplan.acting.loop import BlendedLoop
from btplan.lang import load
from btplan.model import Atom
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS, shape

MOVE_CUBE = ("?", "near(cube)", ("->", "free(tau_cube)", "[MoveTo(cube, tau_cube)]"))
FREE_GOAL = ("not", "blocks(_, tau_goal)")
HOLD_CUBE = ("?", "holding(cube)", ("->", MOVE_CUBE, "hand_empty", "[Pick(cube)]"))
MOVE_GOAL = ("?", "near(goal)", ("->", "free(tau_goal)", "[MoveTo(goal, tau_goal)]"))
FIGURE_7 = ("?", "on(cube, goal)", ("->", HOLD_CUBE, MOVE_GOAL, "[Place(cube, goal)]"))


def loop_for(name: str) -> tuple[BlendedLoop, SymbolicWorld]:
    task = load([str(DOMAINS / name)])
    world = SymbolicWorld(task)
    return BlendedLoop(task, world), world


def test_example_1_grows_the_trees_of_figure_6_then_7() -> None:
    loop, world = loop_for("pick_place.bt")
    assert shape(loop.tree.root) == "on(cube, goal)"  # one goal: no Sequence around it
    trees = []
    while True:
        report = loop.tick()
        if report.expansions:
            trees.append(shape(loop.tree.root))
        if report.status.value == "SUCCESS":
            break
    assert trees[0] == ("?", "on(cube, goal)",
                        ("->", "holding(cube)", "near(goal)", "[Place(cube, goal)]"))
    assert trees[1] == ("?", "on(cube, goal)", ("->", (
        "?", "holding(cube)", ("->", "near(cube)", "hand_empty", "[Pick(cube)]")),
        "near(goal)", "[Place(cube, goal)]"))
    assert trees[-1] == FIGURE_7 and len(trees) == 4
    assert [a.ipc() for a in world.executed] == [
        "(moveto cube tau_cube)", "(pick cube)", "(moveto goal tau_goal)", "(place cube goal)"]


def free(shape_: object, trajectory: str) -> object:
    """A Figure 7 shape with `free(tau)` written as Example 2 does: nothing blocks tau."""
    if shape_ == f"free({trajectory})":
        return ("not", f"blocks(_, {trajectory})")
    if isinstance(shape_, tuple):
        return tuple(free(part, trajectory) for part in shape_)
    return shape_


def obstacle_form(shape_: object) -> object:
    return free(free(shape_, "tau_cube"), "tau_goal")


def test_example_1_structure_holds_in_the_obstacle_domain_without_the_obstacle() -> None:
    loop, _ = loop_for("pick_place_obstacle.bt")
    assert loop.run(100).reached
    assert shape(loop.tree.root) == obstacle_form(FIGURE_7)


def test_example_2_moves_the_new_subtree_before_holding_the_cube() -> None:
    loop, world = loop_for("pick_place_obstacle.bt")
    done: list[int] = []

    def hook(tick: int) -> None:
        if not done and Atom("holding", ("cube",)) in world.facts():
            done.append(tick)
            world.set_fact(Atom("blocks", ("sphere", "tau_goal")))

    seen = []
    result = loop.run(200, before_tick=hook, on_tick=lambda r: seen.extend(r.expansions))
    assert result.reached and done
    clear = next(e for e in seen if e.condition == "not blocks(_, tau_goal)")
    # The paper's actions: the sphere is picked and placed aside, at a target the world
    # chose (not the goal, where the cube must go).
    assert clear.achievers == ["Place(sphere, aside)"]
    assert clear.conflicts_resolved >= 1 and clear.moves == 2
    root = shape(loop.tree.root)
    assert root[0:2] == ("?", "on(cube, goal)")
    place = root[2]
    # Figure 8(b): the path-clearing subtree runs first in the Place sequence, before
    # the holding(cube) subtree; the rest is Figure 7's tree, and MoveTo(goal) still
    # checks the path through the copy the moved subtree left behind.
    assert place[0] == "->" and place[2] == obstacle_form(HOLD_CUBE)
    assert place[1][0:2] == ("?", FREE_GOAL)
    # The alternative for the sphere is guarded by what it is for: blocks(sphere, tau_goal).
    assert place[1][2][1] == "blocks(sphere, tau_goal)"
    assert place[1][2][-1] == "[Place(sphere, aside)]"
    assert place[3] == obstacle_form(MOVE_GOAL)
    assert place[4] == "[Place(cube, goal)]"
    assert [str(a) for a in world.executed] == [
        "MoveTo(cube, tau_cube)", "Pick(cube)",                   # carrying the cube
        "MoveTo(sphere, tau_sphere)", "Drop(cube)",               # approach the sphere, drop
        "Pick(sphere)", "MoveTo(aside, tau_aside)", "Place(sphere, aside)",  # put it aside
        "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]
    assert [e.condition for e in seen][4:] == [
        "not blocks(_, tau_goal)", "holding(sphere)", "near(sphere)", "hand_empty()",
        "near(aside)"]


def test_example_2_right_after_the_expansion_matches_figure_8a_then_8b() -> None:
    loop, world = loop_for("pick_place_obstacle.bt")
    assert loop.run(100).reached  # Example 1's final tree, cube on the goal
    world.clear_fact(Atom("on", ("cube", "goal")))
    world.set_fact(Atom("holding", ("cube",)))
    world.clear_fact(Atom("hand_empty", ()))
    world.clear_fact(Atom("near", ("goal",)))
    world.set_fact(Atom("near", ("cube",)))
    world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
    report = loop.tick()
    assert [e.condition for e in report.expansions] == ["not blocks(_, tau_goal)"]
    place = shape(loop.tree.root)[2]
    assert place[1][1] == FREE_GOAL and place[2] == obstacle_form(HOLD_CUBE)


def test_an_obstacle_put_back_after_it_was_cleared_is_cleared_again_and_others_too() -> None:
    """The guard keeps a cleared obstacle's alternative idle; new blockers get their own."""
    loop, world = loop_for("pick_place_obstacle.bt")
    events = {"sphere": False, "again": False}

    def hook(tick: int) -> None:
        facts = world.facts()
        if not events["sphere"] and Atom("holding", ("cube",)) in facts:
            events["sphere"] = True
            world.set_fact(Atom("blocks", ("sphere", "tau_goal")))
        elif (events["sphere"] and not events["again"]
              and Atom("on", ("sphere", "aside")) in facts
              and Atom("holding", ("cube",)) in facts):
            events["again"] = True  # the sphere rolls back onto the path
            world.clear_fact(Atom("on", ("sphere", "aside")))
            world.set_fact(Atom("blocks", ("sphere", "tau_goal")))

    seen = []
    result = loop.run(300, before_tick=hook, on_tick=lambda r: seen.extend(r.expansions))
    assert result.reached and events["again"]
    executed = [str(a) for a in world.executed]
    assert executed.count("Place(sphere, aside)") == 2
    # The second time the tree already knows how: no new expansion for the path.
    assert [e.condition for e in seen].count("not blocks(_, tau_goal)") == 1


def test_a_failing_action_is_retried_and_a_stuck_one_reported() -> None:
    loop, world = loop_for("pick_place.bt")
    world.fail_next("Pick")
    assert loop.run(100).reached
    assert [str(a) for a in world.failed] == ["Pick(cube)"]
    assert len(loop.expansions) == 4  # the failure cost a retry, not an expansion

    loop, world = loop_for("pick_place.bt")
    for _ in range(10):
        world.fail_next("Pick")
    from btplan.errors import NoProgressError

    try:
        loop.run(200)
    except NoProgressError as error:
        assert "Pick(cube)" in error.reason
    else:
        raise AssertionError("an action that always fails must stop the loop")


def test_an_outside_undo_is_redone_without_expansion() -> None:
    loop, world = loop_for("pick_place.bt")
    undone: list[int] = []

    def hook(tick: int) -> None:
        if not undone and Atom("holding", ("cube",)) in world.facts():
            undone.append(tick)  # the cube slips out of the gripper
            world.clear_fact(Atom("holding", ("cube",)))
            world.set_fact(Atom("hand_empty", ()))

    result = loop.run(100, before_tick=hook)
    assert result.reached and undone
    assert len(loop.expansions) == 4
    assert [str(a) for a in world.executed].count("Pick(cube)") == 2
