"""Every public module, class, function and method of btplan has a docstring.

The Python API reference (docs/reference/api.md) is made from them, and a reader who
follows a name from there into any module should find it explained there too."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def documented_modules() -> list[Path]:
    """The source files behind the reference's `::: btplan.module.Name` lines."""
    names = re.findall(r"^::: (btplan[\w.]*)$", (ROOT / "docs/reference/api.md").read_text(),
                       re.MULTILINE)
    files = set()
    for name in names:
        parts = name.split(".")
        for cut in range(len(parts), 0, -1):
            module = ROOT.joinpath(*parts[:cut])
            for candidate in (module.with_suffix(".py"), module / "__init__.py"):
                if candidate.is_file():
                    files.add(candidate)
                    break
            else:
                continue
            break
    return sorted(files)


def undocumented(path: Path) -> list[str]:
    tree = ast.parse(path.read_text())
    missing = [] if ast.get_docstring(tree) else ["(module)"]

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                if child.name.startswith("_"):
                    continue
                if not ast.get_docstring(child):
                    missing.append(f"{prefix}{child.name} (line {child.lineno})")
                if isinstance(child, ast.ClassDef):
                    visit(child, f"{prefix}{child.name}.")

    visit(tree, "")
    return missing


def test_the_reference_s_modules_document_every_public_name() -> None:
    files = documented_modules()
    assert len(files) >= 20
    gaps = {str(f.relative_to(ROOT)): undocumented(f) for f in files}
    assert {f: g for f, g in gaps.items() if g} == {}


def test_every_module_documents_every_public_name() -> None:
    files = sorted((ROOT / "btplan").rglob("*.py"))
    assert len(files) > 200
    gaps = {str(f.relative_to(ROOT)): undocumented(f) for f in files}
    assert {f: g for f, g in gaps.items() if g} == {}


def test_a_missing_docstring_is_found(tmp_path: Path) -> None:
    module = tmp_path / "m.py"
    module.write_text('"""A module."""\nclass A:\n    """A."""\n    def f(self): pass\n'
                      "def _private(): pass\n")
    assert undocumented(module) == ["A.f (line 4)"]
