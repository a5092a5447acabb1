"""The dependency direction of STYLE.md: lang -> model <- planner -> bt <- worlds, cli on top.

Each rule names the btplan packages a layer must not import; a new forbidden edge fails
here with the module and line that introduced it.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "btplan"

# layer prefix -> btplan modules it must not import
FORBIDDEN: dict[str, tuple[str, ...]] = {
    "btplan.records": ("btplan",),
    "btplan.model": ("btplan",),
    "btplan.atoms": ("btplan",),
    "btplan.errors": ("btplan",),
    "btplan.collector": ("btplan",),
    "btplan.lang": ("btplan.bt", "btplan.planner", "btplan.worlds", "btplan.cli", "btplan.acting",
                    "btplan.sweep"),
    "btplan.bt": ("btplan.model", "btplan.atoms", "btplan.lang", "btplan.planner", "btplan.worlds", "btplan.cli",
                  "btplan.acting", "btplan.sweep"),
    # Grounding a lifted model is beneath both rooms of planning.
    "btplan.grounding": ("btplan.planner", "btplan.classical", "btplan.bt", "btplan.lang",
                         "btplan.worlds", "btplan.cli", "btplan.acting", "btplan.sweep"),
    # The classical planner knows nothing of trees, of PA-BT or of acting.
    "btplan.classical": ("btplan.planner", "btplan.bt", "btplan.lang", "btplan.worlds",
                         "btplan.cli", "btplan.acting", "btplan.sweep", "btplan.robot",
                         "btplan.monitor", "btplan.ros", "btplan.baselines"),
    "btplan.planner": ("btplan.lang", "btplan.worlds", "btplan.cli", "btplan.acting",
                       "btplan.sweep"),
    "btplan.worlds": ("btplan.lang", "btplan.planner", "btplan.cli", "btplan.acting",
                      "btplan.sweep"),
    "btplan.robot": ("btplan.lang", "btplan.planner", "btplan.worlds", "btplan.cli",
                     "btplan.acting", "btplan.sweep"),
    "btplan.acting.loop": ("btplan.cli", "btplan.lang", "btplan.worlds"),
    # Departures see the loop through btplan.acting.state.LoopState and its hooks only.
    "btplan.acting.departures": ("btplan.acting.loop", "btplan.acting.online",
                                 "btplan.acting.offline", "btplan.cli", "btplan.worlds"),
    "btplan.acting.hooks": ("btplan.acting.loop", "btplan.acting.departures"),
    "btplan.acting": ("btplan.cli", "btplan.sweep", "btplan.baselines", "btplan.monitor"),
    # Monitors watch what a run reports (its records, its tree); they never act.
    "btplan.monitor": ("btplan.cli", "btplan.sweep", "btplan.lang", "btplan.planner",
                       "btplan.worlds", "btplan.acting.loop", "btplan.acting.online"),
    "btplan.baselines": ("btplan.cli", "btplan.sweep", "btplan.acting.loop",
                         "btplan.acting.offline", "btplan.acting.online"),
    "btplan.sweep": ("btplan.cli",),
    # The ROS 2 bridge is a robot (btplan.robot) with monitors; it never reaches into the loop.
    "btplan.ros": ("btplan.cli", "btplan.sweep", "btplan.acting", "btplan.planner",
                   "btplan.lang", "btplan.worlds"),
}
ALLOWED_SELF = {"btplan.model", "btplan.errors"}
BENEATH_ALL = "btplan.records"
"""The record classes (a dataclass without its import cost): every layer may build on them."""
MODEL_PARTS = {"btplan.model": "btplan.atoms"}
"""The grounded atoms are the model's own, in a module of their own for size."""


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.extend((node.lineno, alias.name) for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.append((node.lineno, node.module))
            found.extend((node.lineno, f"{node.module}.{a.name}") for a in node.names)
    return found


def within(name: str, prefix: str) -> bool:
    return name == prefix or name.startswith(prefix + ".")


def violations() -> list[str]:
    bad: list[str] = []
    for path in sorted(PACKAGE.rglob("*.py")):
        mod = module_name(path)
        rules = [banned for layer, banned in FORBIDDEN.items() if within(mod, layer)]
        for line, target in imported_modules(path):
            if target == BENEATH_ALL or target.startswith(BENEATH_ALL + "."):
                continue
            if mod in MODEL_PARTS and within(target, MODEL_PARTS[mod]):
                continue
            for banned in (b for rule in rules for b in rule):
                if within(target, banned) and not (mod in ALLOWED_SELF and target == mod):
                    bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {mod} imports {target}")
    return bad


def test_no_forbidden_imports() -> None:
    assert violations() == []


def reaches_into_the_classical_planner(path: Path, mod: str) -> list[str]:
    """Imports of a module behind btplan.classical's names by code outside the package:
    `from btplan.classical.search import ...` or `import btplan.classical.search`."""
    if within(mod, "btplan.classical"):
        return []
    hits = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            targets = [node.module]
        elif isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            continue
        hits += [f"{mod}:{node.lineno} imports {target}" for target in targets
                 if within(target, "btplan.classical") and target != "btplan.classical"]
    return hits


def test_the_pa_bt_steps_use_the_classical_planner_through_its_names_only() -> None:
    """btplan.planner (and the acting layer) ask search, heuristics and mutexes through
    btplan.classical's public names: the search internals can change behind them."""
    assert [hit for path in sorted(PACKAGE.rglob("*.py"))
            for hit in reaches_into_the_classical_planner(path, module_name(path))] == []


def test_a_reach_into_the_classical_planner_is_caught(tmp_path: Path) -> None:
    sample = tmp_path / "sample.py"
    sample.write_text("from btplan.classical.search import SubgoalSearch\n"
                      "from btplan.classical import Portfolio, improve\n"
                      "import btplan.classical.mutex\n")
    assert reaches_into_the_classical_planner(sample, "btplan.planner.sample") == [
        "btplan.planner.sample:1 imports btplan.classical.search",
        "btplan.planner.sample:3 imports btplan.classical.mutex"]
    assert reaches_into_the_classical_planner(sample, "btplan.classical.sample") == []


def test_library_code_never_exits_or_uses_typer() -> None:
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if within(module_name(path), "btplan.cli"):
            continue
        for line, target in imported_modules(path):
            if within(target, "typer"):
                offenders.append(f"{path.name}:{line} imports typer")
        if "sys.exit(" in path.read_text(encoding="utf-8"):
            offenders.append(f"{path.name} calls sys.exit")
    assert offenders == []


@pytest.mark.parametrize("entry", ["btplan", "btplan.cli", "btplan.lang", "btplan.bt"])
def test_heavy_extras_are_not_imported_by_the_core(entry: str) -> None:
    """`btplan check` must work on a bare install: no simulator or plotting imports."""
    heavy = ["pybullet", "ompl", "numpy", "matplotlib", "py_trees", "pyperplan", "behaviortreepy"]
    code = (f"import sys, {entry}; "
            f"print(','.join(m for m in {heavy!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def module_level_imports(path: Path, root: Path = PACKAGE.parent) -> list[str]:
    """btplan modules imported at module level (also under `if TYPE_CHECKING:`), not in functions.

    `from a.b import c` counts as an import of `a.b.c` when that is a module, else of `a.b`.
    Imports inside functions are how heavy or upward-looking code is loaded lazily, and do
    not run when the module is imported, so they cannot close a circle at import time; a
    TYPE_CHECKING import does close one for the type checker and for the reader.
    """
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: list[str] = []

    def visit(nodes: list[ast.stmt]) -> None:
        for node in nodes:
            if isinstance(node, ast.Import):
                found.extend(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                found.extend(f"{node.module}.{a.name}" if is_module(f"{node.module}.{a.name}", root)
                             else node.module for a in node.names)
            elif isinstance(node, ast.If | ast.Try | ast.With):
                for block in ("body", "orelse", "finalbody", "handlers"):
                    for part in getattr(node, block, []):
                        visit(part.body if isinstance(part, ast.ExceptHandler) else [part])

    visit(tree.body)
    return sorted({f for f in found if within(f, "btplan")})


def is_module(name: str, root: Path = PACKAGE.parent) -> bool:
    base = root.joinpath(*name.split("."))
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def import_graph(package: Path = PACKAGE) -> dict[str, list[str]]:
    graph: dict[str, list[str]] = {}
    for path in sorted(package.rglob("*.py")):
        graph[module_name(path)] = [t for t in module_level_imports(path) if t != module_name(path)]
    return graph


def import_circles(graph: dict[str, list[str]]) -> list[list[str]]:
    """Every strongly connected group of more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    circles: list[list[str]] = []

    def connect(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in graph.get(node, []):
            if target not in graph:
                continue
            if target not in index:
                connect(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            group = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                group.append(member)
                if member == node:
                    break
            if len(group) > 1:
                circles.append(sorted(group))

    for node in sorted(graph):
        if node not in index:
            connect(node)
    return sorted(circles)


def test_no_import_circle_among_btplan_modules() -> None:
    assert import_circles(import_graph()) == []


def test_the_circle_check_catches_a_circle_through_type_checking(tmp_path: Path) -> None:
    """Guard against a checker that silently accepts everything."""
    pkg = tmp_path / "btplan" / "w"
    pkg.mkdir(parents=True)
    (tmp_path / "btplan" / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "hub.py").write_text("from btplan.w import leaf\n")
    (pkg / "leaf.py").write_text("from typing import TYPE_CHECKING\n"
                                 "if TYPE_CHECKING:\n    from btplan.w.hub import Hub\n")
    (pkg / "lazy.py").write_text("def f():\n    from btplan.w import hub\n")
    paths = sorted(pkg.rglob("*.py"))
    graph = {".".join(p.relative_to(tmp_path).with_suffix("").parts): [
        t for t in module_level_imports(p, tmp_path) if is_module(t, tmp_path)] for p in paths}
    assert graph["btplan.w.lazy"] == []
    assert import_circles(graph) == [["btplan.w.hub", "btplan.w.leaf"]]
