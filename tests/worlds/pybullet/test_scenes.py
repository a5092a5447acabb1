"""More scenes than the scripted run: other seeds, a cube taken while the arm reaches for
it, an obstacle put back after it was cleared, a shelf the arm must reach round, and a
run that cannot succeed.

Each ends with the goal reached, or with a clear error naming what failed.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from sim_scenes import ROOT, YOUBOT, YOUBOT_SCENE, write_scene, youbot_task
from test_youbot_scenario import act, names
from typer.testing import CliRunner

from btplan.cli import app
from btplan.worlds.pybullet import open_world

TASK = youbot_task()
NO_EVENTS = YOUBOT_SCENE.read_text(encoding="utf-8").split("[[event]]")[0]


@pytest.mark.slow
def test_another_seed_clears_blue_first_and_reaches_the_goal() -> None:
    """bench/sim.py runs seeds 0-9; here one more, after other runs in the same process."""
    world = open_world(TASK, str(YOUBOT_SCENE), seed=1)
    try:
        loop, sizes, _ = act(world)
        cleared = [a.args[0] for a in world.executed
                   if a.name == "Place" and a.args[1].startswith("pose")]
        assert cleared[0] == "blue" and set(cleared) <= {"blue", "red", "yellow"}
        assert names(world.executed)[-2:] == ["MoveTo(goal)", "Place(green, goal)"]
        assert sizes == sorted(sizes)
    finally:
        world.close()


TAKEN = """
[[event]]
name = "agent takes green from under the hand"
when = "near(green)"
delay = 0
do = "move"
cube = "green"
to = [3.0, -1.0]
"""


def test_a_cube_taken_while_the_arm_reaches_for_it_is_followed_and_picked(
        tmp_path: Path) -> None:
    world = open_world(TASK, write_scene(tmp_path, events=TAKEN), seed=1)
    try:
        loop, _, _ = act(world, 400)
        # The cube left from under the fingers: near(green) turned false, Pick was halted.
        assert names(world.halted) == ["Pick(green)"] and world.failed == []
        assert names(world.executed) == ["MoveTo(green)", "MoveTo(green)", "Pick(green)",
                                         "MoveTo(goal)", "Place(green, goal)"]
        assert [e.condition for e in loop.expansions] == [  # none for the disturbance
            "on(green, goal)", "holding(green)", "near(green)", "near(goal)"]
    finally:
        world.close()


PUT_BACK = NO_EVENTS + """
[[event]]
name = "agent puts blue back in the doorway"
when = "holding(green)"
count = 2
do = "move"
cube = "blue"
to = [4.0, 0.0]
"""


@pytest.mark.slow
def test_an_obstacle_put_back_after_it_was_cleared_is_cleared_again(tmp_path: Path) -> None:
    """Through the CLI, as a user runs it; the run depends on the seed (OMPL's paths)."""
    plan, trace = tmp_path / "plan.txt", tmp_path / "trace.jsonl"
    done = subprocess.run([sys.executable, "-m", "btplan", "run", str(YOUBOT), "--sim",
                           "pybullet", "--quiet", "--seed", "0", "--preset", "algorithm1",
                           "--scenario", write_scene(tmp_path, PUT_BACK), "--plan-out", str(plan),
                           "--trace", str(trace)],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    lines = plan.read_text().splitlines()
    places = [line for line in lines if line.startswith("(place blue")]
    # Blue is put aside, pushed back into the doorway when green is picked again, and put
    # aside again at the same pose (checked free again) before green is carried on.
    assert len(places) == 2 and places[0] == places[1]
    assert lines.count("(drop green)") == 2 and lines[-1] == "(place green goal)"
    ticks = [json.loads(line) for line in trace.read_text().splitlines()]
    pushed = next(t["tick"] for t in ticks if t["disturbances"])
    # The subtree that put blue aside, guarded by blocks(blue, t), runs again: no
    # expansion after the push.
    assert not [t for t in ticks if t["tick"] >= pushed and t["expansions"]]


GONE = """
[[event]]
name = "agent takes green away for good"
when = "near(green)"
delay = 2
do = "teleport"
cube = "green"
"""


def test_a_goal_cube_taken_away_for_good_ends_with_exit_1_naming_it(tmp_path: Path) -> None:
    result = CliRunner().invoke(app, ["run", str(YOUBOT), "--sim", "pybullet", "--quiet",
                                      "--scenario", write_scene(tmp_path, events=GONE),
                                      "--max-ticks", "300"])
    assert result.exit_code == 1, result.output
    assert "green" in result.output


def test_a_shelf_over_the_cube_makes_the_arm_reach_along_a_joint_space_plan() -> None:
    """The straight joint move from the folded arm to the cube goes through the board."""
    world = open_world(TASK, str(ROOT / "domains" / "scenes" / "youbot_shelf.toml"), seed=0)
    try:
        act(world, 300)
        assert names(world.executed)[:3] == ["MoveTo(green)", "Pick(green)", "MoveTo(goal)"]
        stats = world.stats()
        assert stats["arm_ompl_followed"] >= 1     # the reach went along OMPL's path
        assert world.check(("on", ("green", "goal")))
    finally:
        world.close()
