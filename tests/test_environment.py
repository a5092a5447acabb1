"""The suite runs on what the project's own install provides, and nothing else.

CI runs on a machine that may have packages installed globally; a test that quietly
imports one of them passes there and fails on a fresh machine. These checks make that
class of mistake fail everywhere: every dependency the project declares must be installed
inside the running venv, and (see conftest.py) no module the suite imported may come
from outside the venv, the checkout, the standard library or a temporary folder.
"""

from __future__ import annotations

import re
import sys
import sysconfig
import tempfile
import tomllib
import types
from importlib import metadata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
IN_VENV = sys.prefix != sys.base_prefix


INTERPRETER_HOOKS = ("sitecustomize", "usercustomize")
"""Modules `site` loads for the interpreter itself, wherever its installation keeps them
(Debian's Python: /etc/python3.X/sitecustomize.py); no install of ours brings them."""


def foreign_modules() -> list[str]:
    """Imported modules whose file lies outside the places a fresh install provides."""
    stdlib = [Path(sysconfig.get_paths()[key]).resolve() for key in ("stdlib", "platstdlib")]
    allowed = [Path(sys.prefix).resolve(), ROOT, Path(tempfile.gettempdir()).resolve()]
    found = []
    for name, module in sorted(sys.modules.items()):
        file = getattr(module, "__file__", None)
        if not file:
            continue
        path = Path(file).resolve()
        if any(path.is_relative_to(root) for root in allowed):
            continue
        in_stdlib = any(path.is_relative_to(root) for root in stdlib)
        in_packages = "site-packages" in path.parts or "dist-packages" in path.parts
        if (in_stdlib or name in INTERPRETER_HOOKS) and not in_packages:
            continue
        found.append(f"{name} ({path})")
    return found


def declared_requirements() -> list[str]:
    """Distribution names that the README's test install (`pip install -e '.[test]'`) asks for.

    The core dependencies and every extra that `test` names, followed through extras that
    name other extras; an extra outside `test` (a large benchmark peer, the type checker)
    is not installed by the README and is not checked.
    """
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extras: dict[str, list[str]] = project.get("optional-dependencies", {})
    specs, todo, seen = list(project["dependencies"]), ["test"], set()
    while todo:
        extra = todo.pop()
        if extra in seen:
            continue
        seen.add(extra)
        for spec in extras.get(extra, []):
            own = re.fullmatch(rf"{project['name']}\[(.*)\]", spec.strip())
            if own:
                todo.extend(name.strip() for name in own.group(1).split(","))
            else:
                specs.append(spec)
    names = {re.split(r"[\s\[<>=!~;]", spec, maxsplit=1)[0] for spec in specs}
    return sorted(names)


def test_the_declared_requirements_are_read() -> None:
    """Guard against a parser that finds nothing and so checks nothing."""
    names = declared_requirements()
    assert {"lark", "pydantic", "typer", "rich", "pytest", "pybullet"} <= set(names)


@pytest.mark.skipif(not IN_VENV, reason="only meaningful inside the README's venv")
@pytest.mark.parametrize("name", declared_requirements())
def test_every_dependency_is_installed_in_the_venv(name: str) -> None:
    dist = metadata.distribution(name)
    location = Path(str(dist.locate_file(""))).resolve()
    assert location.is_relative_to(Path(sys.prefix).resolve()), (
        f"{name} comes from {location}, outside the venv {sys.prefix}: "
        "install it through pyproject.toml"
    )


def test_a_module_from_global_site_packages_is_reported(monkeypatch: pytest.MonkeyPatch) -> None:
    stray = types.ModuleType("stray")
    stray.__file__ = "/opt/elsewhere/lib/python3.11/site-packages/stray.py"
    monkeypatch.setitem(sys.modules, "stray", stray)
    assert any(entry.startswith("stray (") for entry in foreign_modules())
    monkeypatch.delitem(sys.modules, "stray")
    assert not any(entry.startswith("stray (") for entry in foreign_modules())
