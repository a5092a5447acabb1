"""The two-armed cellphone assembly (domains/yumi.bt) in the symbolic world.

The domain never names a handover chain: a part lying opening down must be picked,
handed to the other gripper (which turns it) and inserted by that one. These tests
change only the initial poses and check that handovers appear exactly where a pose
needs one, that a part turned over after it was oriented is oriented again by the
tree it already has, and what happens to a part knocked off the table.
"""

from __future__ import annotations

from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.acting.online import RunOutcome, run
from btplan.model import Literal, Task
from tests.presets import ALGORITHM_1

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
YUMI = load(str(DOMAINS / "yumi.bt"))
PARTS = ("chassis", "board", "battery", "camera", "cover", "screws")


def posed(task: Task, **poses: tuple[str, str]) -> Task:
    """The task with some parts lying elsewhere: part=(place, face).

    A new Task, not a model_copy: a copy would keep the cached initial state.
    """
    init = [f for f in task.problem.init if not (f.predicate == "lies" and f.args[0] in poses)]
    init += [Literal(predicate="lies", args=(p, s, f)) for p, (s, f) in sorted(poses.items())]
    return Task(domain=task.domain, problem=task.problem.model_copy(update={"init": tuple(init)}))


def executed(result: RunOutcome) -> list[str]:
    return [str(a) for a in result.executed]


def handed_over(actions: list[str]) -> list[str]:
    return [a.split("(")[1].split(",")[0] for a in actions if a.startswith("Handover(")]


def assembled(result: RunOutcome) -> bool:
    facts = {str(f) for f in result.world.facts()}
    return result.reached and all(f"mounted({p})" in facts for p in PARTS)


def test_with_every_part_opening_up_no_part_is_handed_over() -> None:
    task = posed(YUMI, chassis=("left_side", "up"), battery=("right_side", "up"))
    result = run(task)
    assert assembled(result)
    assert handed_over(executed(result)) == []
    assert len(result.executed) == 2 * len(PARTS)  # one pick and one insert per part


def test_the_default_scene_needs_one_handover_of_the_chassis() -> None:
    result = run(YUMI)
    assert assembled(result)
    actions = executed(result)
    assert handed_over(actions) == ["chassis"]
    assert actions[:3] == ["Pick(chassis, left, left_side, down, toward)",
                           "Handover(chassis, left, right, toward, away)",
                           "Insert(chassis, right, base, base)"]
    assert len(actions) == 2 * len(PARTS) + 1


def test_two_parts_lying_opening_down_are_each_handed_over_once() -> None:
    task = posed(YUMI, chassis=("left_side", "up"), battery=("right_side", "down"),
                 screws=("middle", "down"))
    result = run(task)
    assert assembled(result)
    actions = executed(result)
    assert handed_over(actions) == ["battery", "screws"]
    pick, give, insert = (actions.index(a) for a in (
        "Pick(battery, right, right_side, down, toward)",
        "Handover(battery, right, left, toward, away)",
        "Insert(battery, left, board, board)"))
    assert pick + 1 == give and give + 1 == insert
    assert len(actions) == 2 * len(PARTS) + 2


def test_with_one_arm_at_the_fixture_parts_are_regrasped_through_the_middle() -> None:
    """Only the right arm mounts: the left arm's parts are put down in the middle for it."""
    task = posed(YUMI, battery=("right_side", "down"))
    init = tuple(f for f in task.problem.init if str(f) != "mounts(left)")
    task = Task(domain=task.domain, problem=task.problem.model_copy(update={"init": init}))
    result = run(task)
    assert assembled(result)
    actions = executed(result)
    assert not any(a.startswith("Insert(") and ", left," in a for a in actions)
    start = actions.index("Pick(battery, right, right_side, down, toward)")
    assert actions[start:start + 5] == [
        "Pick(battery, right, right_side, down, toward)",
        "Place(battery, right, middle, down, toward)",
        "Pick(battery, left, middle, down, toward)",
        "Handover(battery, left, right, toward, away)",
        "Insert(battery, right, board, board)"]
    start = actions.index("Pick(cover, left, left_side, up, away)")
    assert actions[start:start + 4] == [
        "Pick(cover, left, left_side, up, away)", "Place(cover, left, middle, up, away)",
        "Pick(cover, right, middle, up, away)", "Insert(cover, right, battery, camera)"]


def test_the_pddl_twin_gives_the_same_plan() -> None:
    twin = load(str(DOMAINS / "yumi.pddl"))
    ours, theirs = plan(YUMI), plan(twin)
    assert [a.ipc() for a in ours.executed] == [a.ipc() for a in theirs.executed]
    assert [a.ipc() for a in theirs.executed if a.name == "handover"] == [
        "(handover chassis left right toward away)"]


def test_a_chassis_turned_over_in_the_fixture_is_oriented_again_without_expanding() -> None:
    # Algorithm 1's loop, as docs/yumi.md walks through it: the default's watch on the way
    # ahead expands free(right) once more when the flip breaks it ahead of the robot.
    calm = run(YUMI, config=ALGORITHM_1)
    at = next(r.tick for r in calm.records if "Insert(chassis, right, base, base)" in r.finished)
    at += 1
    flip = [f"clear:mounted(chassis)@{at}", f"set:lies(chassis, middle, down)@{at}"]
    result = run(YUMI, disturb=flip, config=ALGORITHM_1)
    assert assembled(result)
    # The tree grows for the later parts exactly as in the calm run, and not for the chassis.
    assert [e.condition for _, e in result.summary().expansions] == [
        e.condition for _, e in calm.summary().expansions]
    after = executed(result)[3:6]
    assert after == ["Pick(chassis, left, middle, down, toward)",
                     "Handover(chassis, left, right, toward, away)",
                     "Insert(chassis, right, base, base)"]
    assert handed_over(executed(result)) == ["chassis", "chassis"]


def test_a_chassis_turned_in_the_gripper_is_handed_back_without_expanding() -> None:
    """The right gripper holds it opening toward: the left Insert's branch has the handover."""
    calm = run(YUMI)
    done = "Handover(chassis, left, right, toward, away)"
    at = next(r.tick for r in calm.records if done in r.finished) + 1
    turn = [f"clear:holds(right, chassis, away)@{at}", f"set:holds(right, chassis, toward)@{at}"]
    result = run(YUMI, disturb=turn)
    assert assembled(result)
    assert [e.condition for _, e in result.summary().expansions] == [
        e.condition for _, e in calm.summary().expansions]
    assert executed(result)[2:4] == ["Handover(chassis, right, left, toward, away)",
                                     "Insert(chassis, left, base, base)"]


def knock(part: str, to: str, at: int) -> list[str]:
    return [f"clear:lies({part}, right_side, up)@{at}", f"set:lies({part}, {to}, up)@{at}"]


def test_a_board_knocked_onto_the_floor_ends_the_run_with_a_reason() -> None:
    result = run(YUMI, disturb=knock("board", "floor", 2), config=ALGORITHM_1)
    assert not result.reached
    assert "mounted(board)" in result.reason
    default = run(YUMI, disturb=knock("board", "floor", 2))  # grown ahead: stuck further on
    assert not default.reached and "board" in default.reason
    assert not any(a.startswith("Pick(board") for a in executed(result))


def test_a_board_knocked_to_the_other_side_is_fetched_by_the_other_arm() -> None:
    result = run(YUMI, disturb=knock("board", "left_side", 2))
    assert assembled(result)
    assert "Pick(board, left, left_side, up, away)" in executed(result)
    assert "Insert(board, left, chassis, chassis)" in executed(result)


def test_the_cli_exits_1_with_one_line_when_a_part_falls_off_the_table() -> None:
    from typer.testing import CliRunner

    from btplan.cli import app

    yumi = str(DOMAINS / "yumi.bt")
    calm = CliRunner().invoke(app, ["run", yumi, "--sim", "symbolic", "--quiet"])
    assert calm.exit_code == 0, calm.output
    fallen = ["--disturb", "clear:lies(board, right_side, up)@2",
              "--disturb", "set:lies(board, floor, up)@2"]
    lost = CliRunner().invoke(app, ["run", yumi, "--sim", "symbolic", "--quiet", *fallen])
    assert lost.exit_code == 1
    assert "mounted(board)" in lost.stderr
    assert "Traceback" not in lost.output
