"""`btplan run --sim pybullet` as a user runs it: exit codes, the plan file, scene errors."""

from __future__ import annotations

from pathlib import Path

import pytest
from sim_scenes import OPEN_ROOM, YOUBOT, write_scene
from typer.testing import CliRunner

from btplan.cli import app


@pytest.mark.slow
def test_the_youbot_run_reaches_the_goal_and_writes_the_executed_plan(tmp_path: Path) -> None:
    plan = tmp_path / "plan.txt"
    result = CliRunner().invoke(app, ["run", str(YOUBOT), "--sim", "pybullet", "--quiet",
                                      "--preset", "algorithm1", "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    lines = plan.read_text().splitlines()
    assert lines[:3] == ["(moveto green traj1)", "(pick green)", "(drop green)"]
    # Obstacles are picked and placed at poses the world sampled off the paths.
    aside = [line.split()[1] for line in lines
             if line.startswith("(place") and line.split()[2].startswith("pose")]
    assert aside == ["blue", "red"]
    assert lines[lines.index("(place blue pose1)") - 3:][:3] == [
        "(moveto blue traj3)", "(pick blue)", "(moveto pose1 traj4)"]
    assert lines[-1] == "(place green goal)"


def test_a_broken_scene_is_bad_input_with_its_location(tmp_path: Path) -> None:
    scene = write_scene(tmp_path, OPEN_ROOM.replace("[2.0, 1.0]", "[2.0]"))
    result = CliRunner().invoke(app, ["run", str(YOUBOT), "--sim", "pybullet", "--quiet",
                                      "--scenario", scene])
    assert result.exit_code == 2
    assert f"{scene}:" in result.output and "'at' must be a list of 2 numbers" in result.output
    assert "Traceback" not in result.output


def test_a_short_budget_is_reported_as_not_reached(tmp_path: Path) -> None:
    result = CliRunner().invoke(app, ["run", str(YOUBOT), "--sim", "pybullet", "--quiet",
                                      "--scenario", write_scene(tmp_path), "--max-ticks", "5"])
    assert result.exit_code == 1
    assert "not reached" in result.output
