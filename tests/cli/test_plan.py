"""`btplan plan`: formats, output files, the executed plan, exit codes, determinism."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from btplan.acting.offline import load
from btplan.bt import SUCCESS
from btplan.bt.formats import load_tree
from btplan.cli import app
from btplan.lang.generators import generate
from btplan.worlds.symbolic import SymbolicWorld

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK = str(DOMAINS / "pick_place.bt")
runner = CliRunner()


def test_plan_prints_json_when_piped_and_the_summary_on_stderr() -> None:
    result = runner.invoke(app, ["plan", PICK])
    assert result.exit_code == 0, result.output
    tree = json.loads(result.stdout)
    assert tree["root"]["type"] == "Fallback"
    assert "4 expansions" in result.stderr and "4 actions executed" in result.stderr


def test_plan_writes_tree_and_ipc_plan_files(tmp_path: Path) -> None:
    out, plan = tmp_path / "tree.xml", tmp_path / "sas_plan"
    result = runner.invoke(app, ["plan", PICK, "-f", "xml", "-o", str(out), "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    assert result.stdout == ""
    assert 'BTCPP_format="4"' in out.read_text()
    assert plan.read_text().splitlines() == [
        "(moveto cube tau_cube)", "(pick cube)", "(moveto goal tau_goal)", "(place cube goal)",
        "; cost = 4 (unit cost)"]


def test_trace_expansions_writes_one_dot_and_json_per_expansion(tmp_path: Path) -> None:
    folder = tmp_path / "steps"
    result = runner.invoke(app, ["plan", PICK, "-f", "ascii", "--trace-expansions", str(folder)])
    assert result.exit_code == 0, result.output
    names = sorted(p.name for p in folder.iterdir())
    assert names == [f"expansion_{i:03d}.{ext}" for i in range(1, 5) for ext in ("dot", "json")]
    first = json.loads((folder / "expansion_001.json").read_text())
    assert first["root"]["type"] == "Fallback"


def test_same_input_and_seed_give_byte_identical_trees() -> None:
    runs = [runner.invoke(app, ["plan", str(DOMAINS / "pick_place_obstacle.bt"), "-f", "dot"])
            for _ in range(2)]
    assert runs[0].exit_code == 0 and runs[0].stdout == runs[1].stdout


def test_missing_file_is_bad_input_and_leaves_no_output(tmp_path: Path) -> None:
    out = tmp_path / "tree.json"
    result = runner.invoke(app, ["plan", str(tmp_path / "nope.bt"), "-o", str(out)])
    assert result.exit_code == 2
    assert "no such file" in result.stderr and not out.exists()
    assert "Traceback" not in result.output


def test_no_achiever_is_a_planning_failure_with_a_reason(tmp_path: Path) -> None:
    source = (DOMAINS / "pick_place.bt").read_text().replace(
        "post: on(o, l), hand_empty, not holding(o)", "post: hand_empty, not holding(o)")
    path = tmp_path / "broken.bt"
    path.write_text(source)
    result = runner.invoke(app, ["plan", str(path)])
    assert result.exit_code == 1
    assert "on(cube, goal)" in result.stderr


def test_budgets_are_enforced_and_reported() -> None:
    result = runner.invoke(app, ["plan", PICK, "--max-expansions", "2"])
    assert result.exit_code == 1 and "expansion budget" in result.stderr
    result = runner.invoke(app, ["plan", PICK, "--max-ticks", "0"])
    assert result.exit_code == 2


def test_plan_reads_pddl_domain_and_problem(tmp_path: Path) -> None:
    from btplan.lang.generators import generate

    domain_text, problem_text = generate("gripper", "pddl", seed=1, balls=3)
    domain, problem = tmp_path / "domain.pddl", tmp_path / "problem.pddl"
    domain.write_text(domain_text)
    problem.write_text(problem_text)
    plan = tmp_path / "plan.txt"
    result = runner.invoke(app, ["plan", str(domain), str(problem), "-f", "ascii",
                                 "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    *steps, cost = plan.read_text().splitlines()
    assert cost == f"; cost = {len(steps)} (unit cost)"
    assert steps and all(s.startswith("(") and s.endswith(")") for s in steps)
    assert {s.split()[0] for s in steps} <= {"(move", "(pick", "(drop"}


def test_an_impossible_swap_exits_1_naming_the_condition(tmp_path: Path) -> None:
    path = tmp_path / "swap.bt"
    path.write_text(SWAP)  # two registers, no spare: the swap cannot be done
    result = runner.invoke(app, ["plan", str(path)])
    assert result.exit_code == 1
    assert "holds(r2, a)" in result.stderr and "Traceback" not in result.output


SWAP = """
domain registers {
    types {
        register
        value
    }
    predicates {
        holds(r: register, v: value)
    }
    action copy(target: register, source: register, v: value, old: value) {
        where: target != source, v != old
        pre:  holds(source, v), holds(target, old)
        post: holds(target, v), not holds(target, old)
    }
}
problem swap for registers {
    objects {
        r1, r2 : register
        a, b : value
    }
    init {
        holds(r1, a), holds(r2, b)
    }
    goal {
        holds(r1, b), holds(r2, a)
    }
}
"""


def test_output_does_not_depend_on_the_hash_seed(tmp_path: Path) -> None:
    import os
    import subprocess
    import sys

    from btplan.lang.generators import generate

    domain_text, problem_text = generate("logistics", "pddl", seed=1, packages=3)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    outputs = []
    for hash_seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": hash_seed}
        done = subprocess.run(
            [sys.executable, "-c", "from btplan.cli import main; main()",
             "plan", "d.pddl", "p.pddl", "-f", "json"],
            cwd=tmp_path, env=env, capture_output=True, text=True, check=True)
        outputs.append(done.stdout)
    assert outputs[0] == outputs[1] and outputs[0].startswith("{")


def test_paper_mode_and_alternatives_are_options() -> None:
    sussman = str(DOMAINS / "planner_sussman.bt")
    assert runner.invoke(app, ["plan", sussman, "--max-alternatives", "2"]).exit_code == 0
    paper = runner.invoke(app, ["plan", sussman, "--paper"])
    assert paper.exit_code == 1 and "conflict" in paper.stderr
    assert runner.invoke(app, ["plan", sussman, "--max-alternatives", "0"]).exit_code == 2


def test_output_format_follows_the_file_extension(tmp_path: Path) -> None:
    for name, start in (("t.xml", "<?xml"), ("t.dot", "digraph"), ("t.json", "{")):
        result = runner.invoke(app, ["plan", PICK, "-o", str(tmp_path / name)])
        assert result.exit_code == 0, result.output
        assert (tmp_path / name).read_text().lstrip().startswith(start)


def test_timeout_zero_means_no_limit_and_a_negative_one_is_refused() -> None:
    result = runner.invoke(app, ["plan", PICK, "--timeout", "0", "-f", "json"])
    assert result.exit_code == 0, result.output
    refused = runner.invoke(app, ["plan", PICK, "--timeout", "-1"])
    assert refused.exit_code == 2
    assert "--timeout must be 0 (no limit) or positive" in refused.stderr


def test_progress_is_shown_once_a_second_after_the_first(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from btplan.acting.offline import load
    from btplan.cli import plan as plan_module
    from btplan.planner import initial_tree

    clock = iter([0.0, 0.5, 1.2, 1.5, 2.4])
    monkeypatch.setattr(plan_module.time, "perf_counter", lambda: next(clock))
    progress = plan_module.Progress()
    tree = initial_tree(load(PICK))
    for _ in range(4):
        progress.update(tree)
    lines = capsys.readouterr().err.splitlines()
    assert lines == [
        "planning: 2 expansions, tree of 1 nodes, 0 conditions failing, 1 s",
        "planning: 4 expansions, tree of 1 nodes, 0 conditions failing, 2 s",
    ]


def _validator() -> Any:
    """bench/validate_plan.py, which shares no code with btplan."""
    path = Path(__file__).resolve().parents[2] / "bench" / "validate_plan.py"
    spec = importlib.util.spec_from_file_location("validate_plan", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["validate_plan"] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module.validate


def _gripper(tmp_path: Path) -> tuple[str, str]:
    domain, problem = generate("gripper", "pddl", seed=0, balls=2)
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    return str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")


def test_the_improved_plan_is_written_and_the_written_tree_executes_it(tmp_path: Path) -> None:
    domain, problem = _gripper(tmp_path)
    tree, plan = tmp_path / "tree.json", tmp_path / "plan"
    result = runner.invoke(app, ["plan", domain, problem, "-o", str(tree), "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    assert "plan improvement removed 2 of 7 steps" in result.stderr
    steps = [s for s in plan.read_text().splitlines() if not s.startswith(";")]
    assert len(steps) == 5
    valid, reason, _ = _validator()(Path(domain).read_text(), Path(problem).read_text(),
                                    plan.read_text())
    assert valid, reason
    task = load(domain, problem)
    world = SymbolicWorld(task)
    saved = load_tree(tree.read_text(), "json")
    for _ in range(20):
        if saved.tick(world) is SUCCESS:
            break
    assert [a.ipc() for a in world.executed] == steps


def test_no_improve_and_paper_keep_the_backchained_plan(tmp_path: Path) -> None:
    domain, problem = _gripper(tmp_path)
    for flag in ("--no-improve", "--paper"):
        plan = tmp_path / f"plan{flag}"
        result = runner.invoke(app, ["plan", domain, problem, "-o", str(tmp_path / "t.json"),
                                     "--plan-out", str(plan), flag])
        assert result.exit_code == 0, result.output
        assert "plan improvement" not in result.stderr
    assert len((tmp_path / "plan--no-improve").read_text().splitlines()) == 7 + 1


def test_the_time_limit_holds_in_a_step_that_never_checks_it(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """Reading and grounding do not look at the clock; the hard limit stops them anyway,
    with exit 1, the phase it stopped in, and nothing written."""
    def endless_load(*paths: str) -> object:
        while True:
            pass

    monkeypatch.setattr("btplan.acting.offline.load", endless_load)
    result = runner.invoke(app, ["plan", str(DOMAINS / "pick_place.bt"), "--timeout", "0.3",
                                 "-q"])
    assert result.exit_code == 1, result.output
    assert "the time limit (0.3 s) was reached while reading the task" in result.output


def test_a_memory_limit_stops_planning_with_exit_1_instead_of_the_oom_killer(
        tmp_path: Path) -> None:
    """200 generated blocks take about 700 MB to plan; under a 150 MB limit the command
    ends with exit 1 naming the limit, and writes nothing. A process of its own: the
    limit is the process's."""
    import subprocess

    for part, flag in (("d.pddl", "--domain-only"), ("p.pddl", "--problem-only")):
        made = runner.invoke(app, ["generate", "blocksworld", "--blocks", "200", "--seed", "1",
                                   flag, "-o", str(tmp_path / part)])
        assert made.exit_code == 0, made.output
    out = tmp_path / "tree.json"
    done = subprocess.run([sys.executable, "-m", "btplan", "plan", str(tmp_path / "d.pddl"),
                           str(tmp_path / "p.pddl"), "-q", "-o", str(out), "--timeout", "0",
                           "--max-memory", "150M"], capture_output=True, text=True, check=False)
    assert done.returncode == 1, done.stderr
    assert "the memory limit (150 MB, --max-memory) ran out while planning" in done.stderr
    assert "Traceback" not in done.stderr and not out.exists()


def test_a_goal_given_on_the_command_line_is_planned_instead_of_the_problems(
        tmp_path: Path) -> None:
    plan = tmp_path / "sas_plan"
    result = runner.invoke(app, ["plan", PICK, "--goal", "(and (holding cube))", "-o",
                                 str(tmp_path / "tree.json"), "--plan-out", str(plan)])
    assert result.exit_code == 0, result.output
    assert plan.read_text().splitlines()[:2] == ["(moveto cube tau_cube)", "(pick cube)"]
    refused = runner.invoke(app, ["plan", PICK, "--goal", "(holding cub)"])
    assert refused.exit_code == 2
    assert "--goal:1:10: unknown object 'cub' in a goal" in refused.stderr
