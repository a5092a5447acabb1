"""The BTPG benchmark runs its btplan half without BTPG, and judges the target as it says."""

from __future__ import annotations

import csv
import importlib.util
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench"


def _load(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(f"bench_{name}", BENCH / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_btplan_half_alone_plans_checks_and_reports_two_goals(tmp_path: Path) -> None:
    out = tmp_path / "rows.csv"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    run = subprocess.run(
        [sys.executable, str(BENCH / "btpg.py"), "--first", "2", "--repeat", "1", "--out",
         str(out)], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0].startswith("btpg_rw_single: 2 goals")
    assert any(line.split()[:2] == ["btplan", "2/2"] for line in lines), run.stdout
    assert any(line.startswith("btplan plan (CLI): summary-line time ") and "- ms" not in line
               for line in lines), run.stdout
    assert lines[-1].endswith("not judged (no BTPG run: give --btpg-src and --btpg-python)")
    rows = list(csv.DictReader(out.open(encoding="utf-8")))
    assert [(r["planner"], r["index"], r["solved"]) for r in rows] == [
        ("btplan", "0", "True"), ("btplan", "1", "True")]
    assert all(float(r["plan_cost"]) > 0 and float(r["seconds"]) > 0 for r in rows)
    assert all(float(r["goal_seconds"]) > 0 for r in rows)
    assert any("the goal alone on the scene read once, then plan(): " in line
               and "- ms" not in line for line in lines), run.stdout


def test_the_target_compares_with_the_btpg_planner_of_lowest_median_time() -> None:
    bench = _load("btpg")
    o = bench.Outcome

    def goal(index: int, mine: float, cost: float) -> list[object]:
        return [o("OBTEA", index, "g", True, 0.002, expansions=2, tree_nodes=5, plan_cost=10),
                o("BTExpansion", index, "g", True, 0.001, expansions=1, tree_nodes=7,
                  plan_cost=10),
                o("btplan", index, "g", True, mine, plan_seconds=mine / 2, expansions=1,
                  tree_nodes=5, plan_cost=cost)]

    met = bench.targets(goal(0, 0.0005, 10) + goal(1, 0.001, 10), "single")
    assert met[0].endswith(": met") and "vs BTExpansion 1.00 ms" in met[1]
    slow_and_dear = bench.targets(goal(0, 0.004, 10) + goal(1, 0.004, 12), "single")
    assert slow_and_dear[0].endswith(": missed")
    assert slow_and_dear[1].endswith("4.0x: missed")
    assert slow_and_dear[-1] == "  plan cost equal to the best BTPG planner's: 1/2 goals: missed"
    lines, ratios = bench.per_goal(goal(0, 0.004, 10))
    assert ratios == {"time": [4.0], "nodes": [1.0], "expansions": [1.0]}
    assert lines[1].split()[2:5] == ["BTExpansion", "1.00", "4.00"]


def test_each_time_is_the_least_of_the_rounds_and_the_rest_the_first_rounds() -> None:
    bench = _load("btpg")
    o = bench.Outcome
    first = [o("btplan", 0, "g", True, 0.004, goal_seconds=0.002, cli_seconds=0.01, plan_cost=10),
             o("OBTEA", 0, "g", True, 0.001, plan_cost=10)]
    second = [o("OBTEA", 0, "g", True, 0.003, plan_cost=10),
              o("btplan", 0, "g", True, 0.003, goal_seconds=0.005, plan_cost=99)]
    merged = {out.planner: out for out in bench.fastest([first, second])}
    assert (merged["btplan"].seconds, merged["btplan"].goal_seconds) == (0.003, 0.002)
    assert merged["btplan"].cli_seconds == 0.01  # the CLI runs in the first round only
    assert merged["btplan"].plan_cost == 10 and merged["OBTEA"].seconds == 0.001


def test_a_btpg_tree_is_counted_and_run_as_btpg_ticks_it() -> None:
    driver = _load("btpg_driver")

    class Leaf:
        def __init__(self, kind: str, content: Any) -> None:
            self.type, self.content = kind, content

        def tick(self, state: set[str]) -> tuple[str, Any]:
            if self.type == "cond":
                return ("success" if self.content <= state else "failure"), self.content
            return "running", self.content

    class Node:
        def __init__(self, kind: str, children: list[object]) -> None:
            self.type, self.children = kind, children

        def tick(self, state: set[str]) -> tuple[str, object]:
            for child in self.children:
                verdict, what = child.tick(state)  # type: ignore[attr-defined]
                if (verdict == "success") == (self.type == "?") or verdict == "running":
                    return verdict, what
            return ("failure" if self.type == "?" else "success"), None

    class Act:
        name = "Make(Water)"
        pre: set[str] = set()
        add = {"Exists(Water)"}
        del_set: set[str] = set()

    tree = Node("?", [Leaf("cond", {"Exists(Water)"}),
                      Node(">", [Leaf("cond", set()), Leaf("act", Act())])])
    assert driver.the_tree(Node("cond", [tree])) is tree
    assert driver.tree_counts(tree) == (5, 2, 1)
    verdict, done = driver.run_tree(tree, set(), lambda s, a: (s | a.add) - a.del_set)
    assert (verdict, [a.name for a in done]) == ("success", ["Make(Water)"])


def test_the_profile_finds_every_phase_and_accounts_for_the_time() -> None:
    profile = _load("btpg_profile")
    folder = profile.DEFAULT_SET
    goals = profile.problems(folder, 2)
    assert [g for g, _ in goals] == ["Low_ACTemperature", "RobotNear_BrightTable2"]
    lines = profile.phase_table(folder, goals[1:], 10.0, 1)
    assert not any(line.startswith("not found in btplan") for line in lines), lines
    phases = {line[:60].strip() for line in lines[3:]}
    for phase in ("reading: s-expressions", "mutexes: h^2", "relaxed model: reachability",
                  "loop: ticks, expansions, tree growth"):
        assert phase in phases, lines
    assert lines[-1].startswith("plan() in all")
