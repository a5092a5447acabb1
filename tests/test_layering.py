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
    "btplan.model": ("btplan",),
    "btplan.errors": ("btplan",),
    "btplan.lang": ("btplan.bt", "btplan.planner", "btplan.worlds", "btplan.cli", "btplan.acting",
                    "btplan.sweep"),
    "btplan.bt": ("btplan.model", "btplan.lang", "btplan.planner", "btplan.worlds", "btplan.cli",
                  "btplan.acting", "btplan.sweep"),
    "btplan.planner": ("btplan.lang", "btplan.worlds", "btplan.cli", "btplan.acting",
                       "btplan.sweep"),
    "btplan.worlds": ("btplan.lang", "btplan.planner", "btplan.cli", "btplan.acting",
                      "btplan.sweep"),
    "btplan.acting.loop": ("btplan.cli", "btplan.lang", "btplan.worlds"),
    "btplan.acting": ("btplan.cli", "btplan.sweep"),
    "btplan.sweep": ("btplan.cli",),
}
ALLOWED_SELF = {"btplan.model", "btplan.errors"}


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
            for banned in (b for rule in rules for b in rule):
                if within(target, banned) and not (mod in ALLOWED_SELF and target == mod):
                    bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {mod} imports {target}")
    return bad


def test_no_forbidden_imports() -> None:
    assert violations() == []


def test_the_rules_catch_an_upward_import(tmp_path: Path) -> None:
    """Guard against a checker that silently accepts everything."""
    sample = tmp_path / "sample.py"
    sample.write_text("from btplan.planner import x\nimport btplan.cli.app\n")
    assert [t for _, t in imported_modules(sample)] == [
        "btplan.planner", "btplan.planner.x", "btplan.cli.app"]


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
