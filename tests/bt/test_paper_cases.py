"""The paper's reactive cases on the hand-built final tree of Example 1 (Figure 7)."""

from __future__ import annotations

from bt_stubs import example1_world, figure7_tree

from btplan.bt import FAILURE, RUNNING, SUCCESS


def executed(log: list[tuple[str, str]]) -> list[str]:
    return [f"{kind} {name}" for kind, name in log if kind != "step"]


def test_figure7_tree_reaches_the_goal_in_order() -> None:
    tree, world = figure7_tree(), example1_world()
    statuses = [tree.tick(world) for _ in range(8)]
    assert statuses == [RUNNING] * 6 + [SUCCESS] * 2
    assert executed(world.log) == ["start MoveTo(cube,tau_cube)", "start Pick(cube)",
                                   "start MoveTo(goal,tau_goal)", "start Place(cube,goal)"]


def test_cube_slipping_mid_moveto_halts_it_and_sends_the_robot_back_to_pick() -> None:
    tree, world = figure7_tree(), example1_world()
    for _ in range(5):  # MoveTo(cube) and Pick done; MoveTo(goal) is under way
        assert tree.tick(world) is RUNNING
    assert world.log[-2:] == [("start", "MoveTo(goal,tau_goal)"),
                              ("step", "MoveTo(goal,tau_goal)")]
    world.facts -= {("holding", ("cube",))}  # the cube slips out of the gripper
    world.facts |= {("hand_empty", ())}
    world.log.clear()
    assert tree.tick(world) is RUNNING
    assert world.log == [("start", "MoveTo(cube,tau_cube)"), ("halt", "MoveTo(goal,tau_goal)")]
    statuses = [tree.tick(world) for _ in range(20)]
    assert statuses.index(SUCCESS) == 5 and FAILURE not in statuses
    assert executed(world.log) == [
        "start MoveTo(cube,tau_cube)", "halt MoveTo(goal,tau_goal)", "start Pick(cube)",
        "start MoveTo(goal,tau_goal)", "start Place(cube,goal)"]


def test_an_external_agent_doing_the_work_skips_the_action() -> None:
    tree, world = figure7_tree(), example1_world()
    tree.tick(world)  # MoveTo(cube) running
    world.facts |= {("holding", ("cube",))}  # someone hands the cube to the robot
    world.facts -= {("hand_empty", ())}
    world.log.clear()
    assert tree.tick(world) is RUNNING
    assert world.log == [("halt", "MoveTo(cube,tau_cube)"), ("start", "MoveTo(goal,tau_goal)")]
