"""`btplan plan` starts lean: it imports what planning needs and nothing heavy besides.

Start-up counts in every whole-process comparison with other planners, and a small
problem plans in less time than rich, pydantic or PyBullet take to import. So the
checks below look at `sys.modules` of a fresh interpreter (not at a clock): after
`import btplan.cli`, and after a whole `btplan plan` run of a small PDDL problem.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from btplan.lang.generators import generate

HEAVY = ("rich", "pydantic", "pybullet", "numpy", "matplotlib", "email", "importlib.metadata",
         "lark", "btplan.lang.bt_reader", "btplan.acting.online", "btplan.worlds.disturb",
         "btplan.bt.formats.btcpp", "btplan.bt.formats.saved", "btplan.acting.live_view",
         "btplan.sweep", "btplan.worlds.pybullet", "typer", "click",
         "dataclasses", "inspect", "tempfile", "difflib", "traceback", "importlib.resources",
         "random", "btplan.lang.writers", "btplan.classical.search", "btplan.planner.rescue",
         "btplan.planner.backjump", "btplan.planner.protect", "btplan.bt.debug",
         "btplan.bt.parallel", "btplan.bt.trace", "btplan.bt.blackboard", "json", "signal",
         "contextvars", "typing")
"""Modules (and their submodules) that neither start-up nor `btplan plan` of well-formed
PDDL needs (lark builds parsers: it reads .bt files and words PDDL syntax errors; typer
builds the command line for help, errors and the other commands, cli/lean.py). The
standard library's share: dataclasses (and inspect beneath it) compile every class's
methods at import, which btplan/records.py avoids; tempfile, difflib (for "did you
mean"), traceback (for --debug) and importlib.resources (for shipped domains by name)
serve only other paths, random only worlds that fail actions on purpose, and btplan's
writers only messages about mistakes; json is imported only for a string the tree
writer cannot write unchanged (or a trace), and the signal handlers and the `--debug`
switch do without `signal`'s enums and `contextvars`. `typing` (4 ms of CPU) is read by
the type checker only: modules name it under `TYPE_CHECKING = False` (a protocol is a
plain base class at run time, and btplan/records.py stands in for the two decorators
it uses). Of the planner, the last-resort search and what
turns its plan into a subtree (search, rescue), the blame of choices when planning stops
(backjump), the `protect_goals` option (protect), `--debug`'s strict world, Parallel
nodes, per-tick traces and the blackboard of BT.CPP trees are imported when first used."""

REPORT = """
import sys
{body}
modules = sorted(sys.modules)
import json
print(json.dumps(modules))
"""


def imported_by(body: str) -> set[str]:
    """The modules a fresh interpreter holds after running `body`."""
    done = subprocess.run([sys.executable, "-c", REPORT.format(body=body)], capture_output=True,
                          text=True, timeout=300, check=True)
    return set(json.loads(done.stdout.splitlines()[-1]))


def heavy(modules: set[str]) -> list[str]:
    return sorted(m for m in modules if any(m == h or m.startswith(h + ".") for h in HEAVY))


def test_importing_the_command_line_imports_no_planner_and_nothing_heavy() -> None:
    modules = imported_by("import btplan.cli")
    assert heavy(modules) == []
    assert not {"btplan.acting", "btplan.planner", "btplan.bt"} & modules


def test_importing_btplan_leaves_the_acting_layer_until_it_is_used() -> None:
    modules = imported_by("import btplan")
    assert "btplan.acting" not in modules
    modules = imported_by("import btplan; btplan.load")
    assert "btplan.acting" in modules


def test_a_whole_plan_run_imports_nothing_heavy(tmp_path: Path) -> None:
    domain_text, problem_text = generate("blocksworld", "pddl", seed=1, blocks=4)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    plan_file = tmp_path / "plan.txt"
    argv = ["btplan", "plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"),
            "-o", str(tmp_path / "tree.json"), "--plan-out", str(plan_file)]
    modules = imported_by(
        f"from btplan.cli import main, lean\nlean.leave = sys.exit\nsys.argv = {argv!r}\n"
        "try:\n    main()\nexcept SystemExit as done:\n    assert done.code == 0, done.code")
    assert plan_file.read_text().startswith("(")  # it did plan
    assert "btplan.planner" in modules
    assert heavy(modules) == []


def test_a_whole_plan_run_compiles_no_source(tmp_path: Path) -> None:
    """Byte code is loaded, never compiled: the first compile of a process costs several
    milliseconds (named tuples and dataclasses compile source when a class is made).
    The one exception is the `__init__` a record class gets once it has made many
    records (btplan/records.py, `<record NAME>`): it is small, and paid back by then."""
    domain_text, problem_text = generate("blocksworld", "pddl", seed=1, blocks=4)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    argv = ["btplan", "plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"),
            "-o", str(tmp_path / "tree.json"), "--plan-out", str(tmp_path / "plan.txt")]
    script = f"""
import compileall, sys
import btplan
compileall.compile_dir(btplan.__path__[0], quiet=1)  # as an installed package has it
compiled = []
sys.addaudithook(lambda event, args: event == "compile" and not str(args[1]).startswith(
    "<record ") and compiled.append(args[1]))
from btplan.cli import lean, main
lean.leave = sys.exit  # raise SystemExit here rather than end the process
sys.argv = {argv!r}
try:
    main()
except SystemExit as done:
    assert done.code == 0, done.code
print(compiled)
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, check=True)
    assert done.stdout.splitlines()[-1] == "[]"


def test_the_console_script_builds_only_the_command_it_runs() -> None:
    script = ("import sys\nfrom btplan.cli import app, only_the_command_asked_for\n"
              "only_the_command_asked_for(sys.argv[1:2])\n"
              "print(len(app.registered_commands) + len(app.registered_groups))\n")
    counts = [subprocess.run([sys.executable, "-c", script, *argv], capture_output=True,
                             text=True, timeout=300, check=True).stdout.strip()
              for argv in (["plan", "x.pddl"], ["generate"], ["--debug", "plan"], ["plna"], [])]
    assert counts == ["1", "1", "7", "7", "7"]


def test_a_misspelt_command_is_still_named_by_the_whole_app() -> None:
    done = subprocess.run([sys.executable, "-m", "btplan", "plna", "x"], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 2 and "No such command 'plna'" in done.stderr


def test_the_collector_is_off_while_starting_and_on_while_planning(tmp_path: Path) -> None:
    """Start-up and reading collect nothing (everything they make lives to the end), but
    planning makes and drops objects: the collector must run then, and a library caller's
    collector is left as it was (also one that calls `main` and catches its exit)."""
    domain_text, problem_text = generate("blocksworld", "pddl", seed=1, blocks=3)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    argv = ["btplan", "plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"),
            "-o", str(tmp_path / "tree.json")]
    script = f"""
import gc, sys
import btplan.acting.offline as offline
seen = []
load, plan = offline.load, offline.plan
def noting_load(*args, **kwargs):
    seen.append(("load", gc.isenabled()))
    return load(*args, **kwargs)
def noting_plan(*args, **kwargs):
    seen.append(("plan", gc.isenabled(), gc.get_threshold()[0]))
    return plan(*args, **kwargs)
offline.load, offline.plan = noting_load, noting_plan
from btplan.cli import lean, main
from btplan.cli.planning import plan_and_write
lean.leave = sys.exit
sys.argv = {argv!r}
try:
    main()
except SystemExit as done:
    assert done.code == 0, done.code
seen.append(("exit", gc.isenabled(), gc.get_threshold()[0]))  # a caller's collector back
plan_and_write(*sys.argv[2:4], out=sys.argv[5], quiet=True)
print(seen)
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, check=True)
    assert done.stdout.splitlines()[-1] == str(
        [("load", False), ("plan", True, 10_000), ("exit", True, 700),
         ("load", True), ("plan", True, 700)])
