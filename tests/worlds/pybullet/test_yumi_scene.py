"""The two-arm assembly (domains/yumi.bt) acted out in PyBullet, headless.

A three-part phone (chassis, board, cover) keeps the runs short; the parts' initial
poses are the problem's `lies` facts, so each test changes only those, and checks the
executed trace: a handover exactly for each part lying opening down, and the phone
assembled, read from the parts' poses on the fixture.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.acting.config import ActingConfig
from btplan.acting.offline import load
from btplan.acting.online import RunOutcome, run
from btplan.cli import app
from btplan.model import Task
from btplan.worlds.pybullet import AssemblyWorld, open_world
from btplan.worlds.pybullet.arm import Timings, straight_free
from btplan.worlds.pybullet.assembly import motions
from btplan.worlds.pybullet.assembly.geometry import down

ROOT = Path(__file__).resolve().parents[3]
YUMI = ROOT / "domains" / "yumi.bt"
SCENE = ROOT / "domains" / "scenes" / "yumi.toml"
PARTS = ("chassis", "board", "cover")
PROBLEM = """
problem three for yumi {{
    objects {{
        left, right : arm
        left_side, right_side, middle, floor : place
        base : fixture
        chassis, board, cover : part
    }}
    init {{
        free(left), free(right)
        reaches(left, left_side), reaches(left, middle)
        reaches(right, right_side), reaches(right, middle)
        grasp_of(up, away), grasp_of(down, toward)
        turned(away, toward), turned(toward, away)
        mounted(base), mounts(left), mounts(right)
        needs(chassis, base, base)
        needs(board, chassis, chassis)
        needs(cover, board, board)
        lies(chassis, left_side, {chassis})
        lies(board, right_side, {board})
        lies(cover, left_side, {cover})
    }}
    goal {{ mounted(chassis), mounted(board), mounted(cover) }}
}}
"""
FLIP = """
[[event]]
name = "someone turns the chassis over"
when = "mounted(chassis)"
do = "flip"
part = "chassis"
to = "middle"
"""


def phone(tmp_path: Path, chassis: str = "up", board: str = "up", cover: str = "up",
          left_mounts: bool = True) -> Task:
    path = tmp_path / "three.bt"
    text = PROBLEM.format(chassis=chassis, board=board, cover=cover)
    path.write_text(text if left_mounts else text.replace("mounts(left), ", ""))
    return load(str(YUMI), str(path), problem="three")


def scene_with(tmp_path: Path, events: str) -> str:
    path = tmp_path / "yumi.toml"
    path.write_text(SCENE.read_text() + events)
    return str(path)


@pytest.fixture
def opened() -> Iterator[list[AssemblyWorld]]:
    worlds: list[AssemblyWorld] = []
    yield worlds
    for world in worlds:
        world.close()


def act(task: Task, opened: list[AssemblyWorld], scene: str | None = None,
        max_ticks: int = 600) -> RunOutcome:
    world = open_world(task, scene)
    assert isinstance(world, AssemblyWorld)
    opened.append(world)
    # Algorithm 1's loop, as docs/yumi.md walks through these scenes.
    return run(task, world=world, agents=world.scene_agents(), max_ticks=max_ticks,
               config=ActingConfig.algorithm1())


def executed(result: RunOutcome) -> list[str]:
    return [str(a) for a in result.executed]


def handed_over(result: RunOutcome) -> list[str]:
    return [a.args[0] for a in result.executed if a.name == "Handover"]


def assembled(result: RunOutcome) -> bool:
    """Read from the scene: every part rests on the fixture's stack, opening up."""
    state = result.world.state
    heights = [state.pose(p)[0][2] for p in PARTS]
    return result.reached and all(state.mounted(p) for p in PARTS) and heights == sorted(heights)


@pytest.mark.slow
def test_parts_lying_opening_up_are_assembled_with_no_handover(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    result = act(phone(tmp_path), opened)
    assert assembled(result), result.reason
    assert handed_over(result) == []
    assert len(result.executed) == 2 * len(PARTS)


@pytest.mark.slow
def test_a_chassis_lying_opening_down_is_handed_over_once(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    result = act(phone(tmp_path, chassis="down"), opened)
    assert assembled(result), result.reason
    assert executed(result)[:3] == ["Pick(chassis, left, left_side, down, toward)",
                                    "Handover(chassis, left, right, toward, away)",
                                    "Insert(chassis, right, base, base)"]
    assert handed_over(result) == ["chassis"]


@pytest.mark.slow
def test_two_parts_lying_opening_down_are_each_handed_over(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    result = act(phone(tmp_path, board="down", cover="down"), opened)
    assert assembled(result), result.reason
    assert handed_over(result) == ["board", "cover"]
    assert executed(result)[2:5] == ["Pick(board, right, right_side, down, toward)",
                                     "Handover(board, right, left, toward, away)",
                                     "Insert(board, left, chassis, chassis)"]
    assert len(result.executed) == 2 * len(PARTS) + 2


@pytest.mark.slow
def test_with_only_the_right_arm_at_the_fixture_the_left_puts_parts_down_in_the_middle(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    result = act(phone(tmp_path, cover="down", left_mounts=False), opened)
    assert assembled(result), result.reason
    assert executed(result)[:4] == ["Pick(chassis, left, left_side, up, away)",
                                    "Place(chassis, left, middle, up, away)",
                                    "Pick(chassis, right, middle, up, away)",
                                    "Insert(chassis, right, base, base)"]
    assert executed(result)[-3:] == ["Pick(cover, left, left_side, down, toward)",
                                     "Handover(cover, left, right, toward, away)",
                                     "Insert(cover, right, board, board)"]
    assert result.world.halted == [] and result.world.failed == []


@pytest.mark.slow
def test_a_chassis_turned_over_after_it_was_mounted_is_oriented_again_without_expanding(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    task = phone(tmp_path, chassis="down")
    calm = act(task, opened)
    result = act(task, opened, scene_with(tmp_path, FLIP))
    assert assembled(result), result.reason
    assert [d.description for r in result.records for d in r.disturbances] == [
        "someone turns the chassis over: turns over chassis, now in middle opening down"]
    assert [e.condition for _, e in result.summary().expansions] == [
        e.condition for _, e in calm.summary().expansions]
    assert executed(result)[3:6] == ["Pick(chassis, left, middle, down, toward)",
                                     "Handover(chassis, left, right, toward, away)",
                                     "Insert(chassis, right, base, base)"]


def knock(to: str) -> str:
    """An event that knocks the board (lying opening up) to `to` once the chassis is in."""
    return FLIP.replace("turns the chassis over", f"knocks the board to {to}").replace(
        '"flip"', '"knock"').replace('part = "chassis"', 'part = "board"').replace(
        '"middle"', f'"{to}"')


@pytest.mark.slow
def test_a_board_knocked_off_the_table_ends_the_run_with_exit_1_naming_it(
        tmp_path: Path) -> None:
    domain = YUMI.read_text().split("\nproblem phone")[0]
    phone(tmp_path)
    both = tmp_path / "three_parts.bt"
    both.write_text(domain + (tmp_path / "three.bt").read_text())
    plan = tmp_path / "plan.txt"
    result = CliRunner().invoke(app, ["run", str(both), "--sim", "pybullet", "--quiet", "--preset", "algorithm1",
                                      "--scenario", scene_with(tmp_path, knock("floor")),
                                      "--plan-out", str(plan)])
    assert result.exit_code == 1, result.output
    failed = [line for line in result.stderr.splitlines() if line.startswith("failed:")]
    assert len(failed) == 1
    assert "holds(left, board, away) or holds(right, board, away)" in failed[0]
    assert "Traceback" not in result.output
    assert plan.read_text().splitlines() == ["(pick chassis left left_side up away)",
                                             "(insert chassis left base base)"]


@pytest.mark.slow
def test_a_board_knocked_to_the_other_side_is_fetched_by_the_other_arm(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    result = act(phone(tmp_path), opened, scene_with(tmp_path, knock("left_side")))
    assert assembled(result), result.reason
    assert "Insert(board, left, chassis, chassis)" in executed(result)


@pytest.mark.slow
def test_an_arm_move_blocked_by_the_other_arm_is_planned_around_it_with_ompl(
        tmp_path: Path, opened: list[AssemblyWorld]) -> None:
    world = open_world(phone(tmp_path))
    assert isinstance(world, AssemblyWorld)
    opened.append(world)
    state, timings = world.state, Timings()
    left, right = state.arm("left"), state.arm("right")
    reaching_over = right.solve_ik((-0.15, 0.0, 0.25), down(0.0))  # into the left arm's half
    goal = left.solve_ik((-0.2, 0.25, 0.08), down(0.0))
    assert reaching_over is not None and goal is not None
    right.set_arm(reaching_over)
    right.command(reaching_over)
    bodies = motions.obstacles(state, "left")

    def free(q: tuple[float, ...]) -> bool:
        return not left.touches(q, bodies, state.sim.table)

    assert not straight_free(left.joints(), goal, free)
    path = motions.plan(state, timings, "left", goal)
    assert path is not None and len(path) > 2 and timings.ompl_solves == 1
    assert all(straight_free(a, b, free) for a, b in zip(path, path[1:]))
    touched = False
    for _ in motions.follow(state, "left", path):
        state.sim.step()
        touched |= bool(state.sim.p.getContactPoints(left.body, right.body,
                                                     physicsClientId=state.sim.client))
    assert not touched
    assert max(abs(a - b) for a, b in zip(left.joints(), goal)) < 0.06


@pytest.mark.slow
def test_the_default_run_hands_the_chassis_over_and_assembles_the_phone(tmp_path: Path) -> None:
    plan = tmp_path / "plan.txt"
    result = CliRunner().invoke(app, ["run", str(YUMI), "--sim", "pybullet", "--quiet",
                                      "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    lines = plan.read_text().splitlines()
    assert [line for line in lines if line.startswith("(handover")] == [
        "(handover chassis left right toward away)"]
    assert sum(line.startswith("(insert") for line in lines) == 6


def test_a_broken_assembly_scene_is_bad_input_with_its_location(tmp_path: Path) -> None:
    scene = tmp_path / "yumi.toml"
    scene.write_text(SCENE.read_text().replace("size = [0.12, 0.045, 0.015]",
                                               "size = [0.12, 0.2, 0.015]"))
    result = CliRunner().invoke(app, ["run", str(YUMI), "--sim", "pybullet", "--quiet",
                                      "--scenario", str(scene)])
    assert result.exit_code == 2
    line = 1 + SCENE.read_text().split("\n").index("size = [0.12, 0.045, 0.015]")
    assert f"{scene}:{line}:" in result.output and "the grippers open 8 cm" in result.output
    assert "Traceback" not in result.output


def test_a_part_of_the_problem_missing_from_the_scene_is_named(tmp_path: Path) -> None:
    scene = tmp_path / "yumi.toml"
    scene.write_text(SCENE.read_text().replace('name = "screws"', 'name = "bolts"'))
    result = CliRunner().invoke(app, ["run", str(YUMI), "--sim", "pybullet", "--quiet",
                                      "--scenario", str(scene)])
    assert result.exit_code == 2
    assert "'screws' is a part of the problem but not in the scene" in result.output
    assert "Traceback" not in result.output


@pytest.mark.slow
def test_record_films_both_arms_from_the_front(tmp_path: Path) -> None:
    movie = tmp_path / "start.gif"
    result = CliRunner().invoke(app, ["run", str(YUMI), "--sim", "pybullet", "--quiet", "--preset", "algorithm1",
                                      "--record", str(movie), "--max-ticks", "12"])
    assert result.exit_code == 1  # the phone is not built in 12 ticks; the movie is still saved
    from PIL import Image

    with Image.open(movie) as gif:
        # Ticks 1 to 4 only grow the tree; then 8 ticks of Pick, one frame every 2.
        assert gif.size == (640, 400) and gif.n_frames == 4
        assert len(gif.convert("RGB").getcolors(1 << 16) or ()) > 50  # a picture, not a blank
