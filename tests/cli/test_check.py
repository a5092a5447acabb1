"""`btplan check`: exit 0 and a summary on good input, exit 2 and a located error on bad input."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from btplan.cli import app

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
runner = CliRunner()


def test_every_bundled_domain_checks() -> None:
    files = sorted(str(p) for p in DOMAINS.glob("*.bt"))
    result = runner.invoke(app, ["check", *files])
    assert result.exit_code == 0, result.output
    for name in ("pick_place", "blocksworld", "gripper", "logistics", "sussman"):
        assert name in result.stdout


def test_summary_names_types_predicates_actions_and_goal() -> None:
    result = runner.invoke(app, ["check", str(DOMAINS / "pick_place.bt")])
    assert result.exit_code == 0
    out = result.stdout
    assert "domain pick_place" in out
    assert "types       3: location, object, trajectory" in out
    assert "actions     3: MoveTo, Pick, Place" in out
    assert "problem cube_on_goal for pick_place" in out
    assert "goal        1: on(cube, goal)" in out


def test_json_prints_the_parsed_models() -> None:
    result = runner.invoke(app, ["check", "--json", str(DOMAINS / "pick_place.bt")])
    assert result.exit_code == 0
    data = json.loads(result.stdout)
    assert [a["name"] for a in data["domains"][0]["actions"]] == ["MoveTo", "Pick", "Place"]
    assert data["problems"][0]["goal"] == [
        {"predicate": "on", "args": ["cube", "goal"], "positive": True}
    ]


def test_bad_input_exits_2_with_location_line_and_caret(tmp_path: Path) -> None:
    bad = tmp_path / "bad.bt"
    bad.write_text(
        (DOMAINS / "pick_place.bt")
        .read_text()
        .replace("pre:  holding(o), near(l)", "pre:  holdng(o), near(l)")
    )
    result = runner.invoke(app, ["check", str(bad)])
    assert result.exit_code == 2
    lines = result.stderr.splitlines()
    assert lines[0] == f"error: {bad}:41:15: unknown predicate 'holdng' (did you mean 'holding'?)"
    assert lines[1] == "          pre:  holdng(o), near(l)"
    assert lines[2] == "                ^"
    assert "Traceback" not in result.output


def test_pddl_pair_checks(tmp_path: Path) -> None:
    domain = tmp_path / "d.pddl"
    problem = tmp_path / "p.pddl"
    runner.invoke(app, ["generate", "gripper", "--balls", "3", "--domain-only", "-o", str(domain)])
    runner.invoke(
        app, ["generate", "gripper", "--balls", "3", "--problem-only", "-o", str(problem)]
    )
    result = runner.invoke(app, ["check", str(domain), str(problem)])
    assert result.exit_code == 0, result.output
    assert "gripper_3_s0" in result.stdout


def test_missing_file_is_bad_input(tmp_path: Path) -> None:
    result = runner.invoke(app, ["check", str(tmp_path / "nope.bt")])
    assert result.exit_code == 2
    assert "no such file" in result.stderr


def test_every_error_is_printed_with_a_count(tmp_path: Path) -> None:
    bad = tmp_path / "bad.bt"
    bad.write_text(
        (DOMAINS / "pick_place.bt")
        .read_text()
        .replace("pre:   free(t)", "pre:   fre(t)")
        .replace("on(cube, goal)\n", "on(cub, goal)\n")
    )
    result = runner.invoke(app, ["check", str(bad)])
    assert result.exit_code == 2
    errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
    assert errors == [
        f"error: {bad}:29:16: unknown predicate 'fre' (did you mean 'free'?)",
        f"error: {bad}:60:12: unknown object 'cub' in a goal (did you mean 'cube'?)",
    ]
    assert result.stderr.splitlines()[-1] == "2 errors"


def test_standard_input_in_either_language() -> None:
    text = (DOMAINS / "pick_place.bt").read_text()
    result = runner.invoke(app, ["check", "-"], input=text)
    assert result.exit_code == 0 and "problem cube_on_goal for pick_place" in result.stdout
    pddl = runner.invoke(app, ["generate", "logistics", "--packages", "2"]).stdout
    result = runner.invoke(app, ["check", "-"], input=pddl)
    assert result.exit_code == 0 and "problem logistics_2_s0 for logistics" in result.stdout


def test_warnings_go_to_stderr_and_keep_exit_0(tmp_path: Path) -> None:
    path = tmp_path / "static_goal.bt"
    path.write_text(
        (DOMAINS / "pick_place.bt")
        .read_text()
        .replace("on(cube, goal)\n", "route(cube, tau_goal)\n")
    )
    result = runner.invoke(app, ["check", str(path)])
    assert result.exit_code == 0
    assert result.stderr.startswith(
        f"warning: {path}:60:9: the goal 'route(cube, tau_goal)' can never hold"
    )
    assert "ok: 2 definitions checked" in result.stdout


def test_a_newline_in_a_path_keeps_the_message_on_one_line(tmp_path: Path) -> None:
    odd = str(tmp_path / "a\nb.bt")
    result = runner.invoke(app, ["check", odd])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "a\\nb.bt:1:1: no such file" in lines[0]
