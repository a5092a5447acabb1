"""`btplan run`: exit codes, the summary, the trace file, the plan file, located spec errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.cli import app

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK_PLACE = str(DOMAINS / "pick_place.bt")
runner = CliRunner()

PLAN = "(moveto cube tau_cube)\n(pick cube)\n(moveto goal tau_goal)\n(place cube goal)\n"


def test_a_calm_run_reaches_the_goal_and_writes_the_executed_plan(tmp_path: Path) -> None:
    plan = tmp_path / "sas_plan"
    result = runner.invoke(app, ["run", PICK_PLACE, "--sim", "symbolic", "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    assert plan.read_text() == PLAN
    assert result.stdout == ""
    assert "goal reached" in result.stderr
    assert "expansions          4 (on(cube, goal) @1" in result.stderr


def test_the_plan_can_go_to_standard_output() -> None:
    result = runner.invoke(app, ["run", PICK_PLACE, "--quiet", "--plan-out", "-"])
    assert result.exit_code == 0
    assert result.stdout == PLAN


def test_the_trace_has_one_json_line_per_tick_with_the_disturbance(tmp_path: Path) -> None:
    trace = tmp_path / "run.jsonl"
    result = runner.invoke(app, ["run", PICK_PLACE, "--paper", "--disturb", "undo:Pick@8",
                                 "--trace", str(trace)])
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in trace.read_text().splitlines()]
    assert [line["tick"] for line in lines] == list(range(1, len(lines) + 1))
    assert lines[-1]["status"] == "SUCCESS"
    assert lines[7]["disturbances"] == [
        {"agent": "undo:Pick@8", "kind": "undo",
         "description": "undid Pick(cube): +hand_empty() -holding(cube)"}]
    assert lines[0]["expansions"][0]["condition"] == "on(cube, goal)"
    assert {"id", "kind", "name", "status"} <= set(lines[3]["nodes"][0])
    assert "tick 8: undo:Pick@8: undid Pick(cube)" in result.stderr


def test_a_scenario_file_adds_agents(tmp_path: Path) -> None:
    scenario = tmp_path / "help.dist"
    scenario.write_text("# someone hands the cube over\nhelp:Pick(cube)@1\n")
    result = runner.invoke(app, ["run", PICK_PLACE, "--scenario", str(scenario), "--quiet",
                                 "--plan-out", "-"])
    assert result.exit_code == 0, result.output
    assert result.stdout == "(moveto goal tau_goal)\n(place cube goal)\n"


def test_not_reaching_the_goal_in_time_exits_1_and_still_writes_the_trace(tmp_path: Path) -> None:
    trace = tmp_path / "short.jsonl"
    result = runner.invoke(app, ["run", PICK_PLACE, "--max-ticks", "5", "--trace", str(trace)])
    assert result.exit_code == 1
    assert "not reached" in result.stderr
    assert "within 5 ticks" in result.stderr
    assert len(trace.read_text().splitlines()) == 5


def test_a_bad_spec_is_a_located_error_and_nothing_is_written(tmp_path: Path) -> None:
    trace = tmp_path / "never.jsonl"
    result = runner.invoke(app, ["run", PICK_PLACE, "--disturb", "undo@5x",
                                 "--trace", str(trace)])
    assert result.exit_code == 2
    assert "--disturb:1:7: unexpected 'x' after the timing" in result.stderr
    assert "  undo@5x\n        ^" in result.stderr
    assert not trace.exists()
    assert "Traceback" not in result.output


def test_a_spec_naming_an_unknown_action_gets_a_hint() -> None:
    result = runner.invoke(app, ["run", PICK_PLACE, "--disturb", "fail:Pik@2"])
    assert result.exit_code == 2
    assert "unknown action 'Pik' (did you mean 'Pick'?)" in result.stderr


def test_a_bad_scenario_line_points_at_the_file_line(tmp_path: Path) -> None:
    scenario = tmp_path / "bad.dist"
    scenario.write_text("undo@3\n  clear:holding(cube)@ten\n")
    result = runner.invoke(app, ["run", PICK_PLACE, "--scenario", str(scenario)])
    assert result.exit_code == 2
    assert f"{scenario}:2:23: expected a tick number" in result.stderr


def test_failure_probabilities_are_checked() -> None:
    bad = runner.invoke(app, ["run", PICK_PLACE, "--fail-prob", "Pick=2"])
    assert bad.exit_code == 2 and "between 0 and 1" in bad.stderr
    unknown = runner.invoke(app, ["run", PICK_PLACE, "--fail-prob", "Pock=0.5"])
    assert unknown.exit_code == 2 and "unknown action 'Pock'" in unknown.stderr


def test_a_sure_failure_of_the_only_achiever_ends_with_a_reason() -> None:
    result = runner.invoke(app, ["run", PICK_PLACE, "--fail-prob", "Pick=1", "--quiet"])
    assert result.exit_code == 1
    failed_row = next(line for line in result.stderr.splitlines() if line.startswith(" failed"))
    assert "Pick(cube)" in failed_row
    assert "MoveTo(cube, tau_cube)" in result.stderr


def test_gui_needs_the_pybullet_world() -> None:
    result = runner.invoke(app, ["run", PICK_PLACE, "--gui"])
    assert result.exit_code == 2
    assert "--gui and --record need --sim pybullet" in result.stderr


def test_a_pybullet_run_without_a_scene_is_a_clean_error() -> None:
    result = runner.invoke(app, ["run", PICK_PLACE, "--sim", "pybullet", "--quiet"])
    assert result.exit_code == 2
    assert "no scene for domain 'pick_place'" in result.stderr
    assert "Traceback" not in result.output


@pytest.mark.slow
def test_a_pybullet_run_acts_with_the_scene_agents(tmp_path: Path) -> None:
    trace = tmp_path / "youbot.jsonl"
    result = runner.invoke(app, ["run", str(DOMAINS / "youbot.bt"), "--sim", "pybullet",
                                 "--scenario", "youbot", "--quiet", "--trace", str(trace)])
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in trace.read_text().splitlines()]
    kinds = [d for line in lines for d in line["disturbances"]]
    assert kinds, "the scene's scripted agents should have acted"
    assert lines[-1]["status"] == "SUCCESS"
    assert any(e["condition"].startswith("not blocks(_, ")
               for line in lines for e in line["expansions"])


def test_the_default_grows_the_tree_within_a_tick_and_watches_the_way_ahead(
        tmp_path: Path) -> None:
    obstacle = str(DOMAINS / "pick_place_obstacle.bt")

    def expansions(*flags: str) -> list[tuple[int, list[str]]]:
        trace = tmp_path / "run.jsonl"
        result = runner.invoke(app, ["run", obstacle, "--disturb",
                                     "set:blocks(sphere, tau_goal)@3", "-q",
                                     "--trace", str(trace), *flags])
        assert result.exit_code == 0, result.output
        lines = [json.loads(line) for line in trace.read_text().splitlines()]
        return [(line["tick"], [e["condition"] for e in line["expansions"]])
                for line in lines if line["expansions"]]

    plain, extended = expansions("--paper"), expansions()
    # --paper: one expansion per tick, the blocked path met only when MoveTo(goal) is next.
    assert all(len(conditions) == 1 for _, conditions in plain)
    assert ("not blocks(_, tau_goal)" in dict(plain)[8])
    # Default: the whole plan at tick 1, the blocked path the tick the agent blocks it.
    tick, conditions = extended[0]
    assert tick == 1 and sorted(conditions) == [
        "holding(cube)", "near(cube)", "near(goal)", "on(cube, goal)"]
    assert extended[1][0] == 3 and extended[1][1][0] == "not blocks(_, tau_goal)"


def test_the_default_retries_a_failing_action_within_the_tick_budget() -> None:
    flags = ["run", PICK_PLACE, "--disturb", "fail:Pick@1..8", "--quiet"]
    plain = runner.invoke(app, [*flags, "--paper"])
    assert plain.exit_code == 1
    assert "failed 4 ticks in a row" in plain.stderr
    extended = runner.invoke(app, flags)
    assert extended.exit_code == 0, extended.output
    assert "goal reached" in extended.stderr


@pytest.mark.slow
def test_the_default_in_pybullet_clears_the_doorway_before_it_picks_green() -> None:
    result = runner.invoke(app, ["run", str(DOMAINS / "youbot.bt"), "--sim", "pybullet",
                                 "--quiet", "--plan-out", "-"])
    assert result.exit_code == 0, result.output
    plan = result.stdout.splitlines()
    assert plan[:2] == ["(moveto blue traj3)", "(pick blue)"]
    assert plan[-1] == "(place green goal)"


def test_on_a_terminal_the_live_view_draws_the_tree(monkeypatch: pytest.MonkeyPatch) -> None:
    from io import StringIO

    from rich.console import Console

    import btplan.cli.run as run_command
    from btplan.cli.console import LazyConsole

    screen = StringIO()
    terminal = Console(file=screen, force_terminal=True, width=100, color_system=None)
    monkeypatch.setattr(run_command, "stderr", LazyConsole(stderr=True, rich=terminal))
    result = runner.invoke(app, ["run", PICK_PLACE, "--paper", "--disturb", "undo:Pick@11"])
    assert result.exit_code == 0, result.output
    shown = screen.getvalue()
    assert "tick 17  SUCCESS" in shown
    assert "[Place(cube, goal)]  SUCCESS" in shown
    assert "undid Pick(cube)" in shown
    assert "goal reached" in shown


@pytest.mark.parametrize(("scenario", "flags", "blocked", "undone"),
                         [("example2.dist", [], 5, 15),
                          ("example2_paper.dist", ["--paper"], 8, 23)])
def test_the_example_2_scenario_grows_the_tree_once_and_survives_the_undo(
        tmp_path: Path, scenario: str, flags: list[str], blocked: int, undone: int) -> None:
    trace = tmp_path / "example2.jsonl"
    result = runner.invoke(app, ["run", str(DOMAINS / "pick_place_obstacle.bt"), "--scenario",
                                 str(DOMAINS.parent / "examples" / scenario), "--quiet",
                                 "--trace", str(trace), *flags])
    assert result.exit_code == 0, result.output
    lines = [json.loads(line) for line in trace.read_text().splitlines()]
    grown = {line["tick"]: [e["condition"] for e in line["expansions"]] for line in lines
             if line["expansions"]}
    assert grown[blocked][0] == "not blocks(_, tau_goal)"
    assert max(grown) < undone, f"the undo at tick {undone} must not expand the tree"
    assert [d["kind"] for line in lines for d in line["disturbances"]] == ["set", "undo"]
    assert lines[undone - 1]["facts"]["removed"] == ["holding(cube)"]


def test_the_same_seed_gives_the_same_trace_in_any_process(tmp_path: Path) -> None:
    """Byte-identical traces even when Python's string hashing differs between processes."""
    import os
    import subprocess
    import sys

    texts = []
    for hash_seed in ("1", "2"):
        trace = tmp_path / f"run{hash_seed}.jsonl"
        subprocess.run(
            [sys.executable, "-c", "from btplan.cli import main; main()", "run",
             str(DOMAINS / "pick_place_obstacle.bt"), "--quiet", "--seed", "5",
             "--disturb", "undo@p=0.1", "--disturb", "help@p=0.05",
             "--scenario", str(DOMAINS.parent / "examples" / "example2_paper.dist"), "--paper",
             "--trace", str(trace)],
            env={**os.environ, "PYTHONHASHSEED": hash_seed}, capture_output=True, check=True)
        texts.append(trace.read_text())
    assert texts[0] == texts[1]
    kinds = [d["kind"] for line in texts[0].splitlines()
             for d in json.loads(line)["disturbances"]]
    assert {"set", "undo", "help"} <= set(kinds)


def test_the_pybullet_world_on_a_domain_it_does_not_serve_points_at_your_own_robot() -> None:
    pytest.importorskip("pybullet")
    fetch = str(DOMAINS / "fetch_cup.bt")
    no_scene = runner.invoke(app, ["run", fetch, "--sim", "pybullet", "-q"])
    assert no_scene.exit_code == 2
    assert "youbot.bt" in no_scene.output and "docs/robot.md" in no_scene.output
    other = runner.invoke(app, ["run", fetch, "--sim", "pybullet", "-q", "--scenario",
                                str(DOMAINS / "scenes" / "youbot.toml")])
    assert other.exit_code == 2
    assert "cannot measure: at, delivered" in other.output and "--world" in other.output
    assert "Traceback" not in other.output


def test_a_tick_that_does_not_end_is_cut_by_the_time_budget(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """The run stops itself at the first tick after --timeout; a tick that never ends
    (an expansion that goes on and on) is cut by the timer, the skills halted."""
    from btplan.acting.loop import BlendedLoop

    def endless(self: BlendedLoop) -> None:
        while True:
            pass

    monkeypatch.setattr(BlendedLoop, "tick", endless)
    result = runner.invoke(app, ["run", PICK_PLACE, "-q", "--timeout", "0.2"])
    assert result.exit_code == 1, result.output
    assert "the time budget (0.2 s) ran out in the middle of a tick" in result.output


def test_a_run_acts_toward_a_goal_given_on_the_command_line(tmp_path: Path) -> None:
    plan = tmp_path / "plan.txt"
    result = runner.invoke(app, ["run", str(DOMAINS / "pick_place.bt"), "--goal",
                                 "(holding cube)", "--plan-out", str(plan), "-q"])
    assert result.exit_code == 0, result.output
    assert plan.read_text().splitlines()[:2] == ["(moveto cube tau_cube)", "(pick cube)"]
    refused = runner.invoke(app, ["run", str(DOMAINS / "pick_place.bt"), "--goal", "(holding)"])
    assert refused.exit_code == 2
    assert "--goal:1:2: holding takes 1 argument, got 0" in refused.stderr
