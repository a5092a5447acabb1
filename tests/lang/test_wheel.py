"""A non-editable install works from any folder: grammars, domains and scenes are package data.

Builds the wheel from a copy of the sources (so the working tree stays clean), installs
it with --no-deps into a fresh, isolated venv, and runs a check from an unrelated folder.
The new venv borrows its dependencies from the interpreter running the suite (a path line
in a .pth file), never from the machine's global site-packages: a venv that sees the
system's packages, made from the README's .venv, would see the base interpreter's
packages instead, and the test would pass only where lark happens to be installed
globally.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run(*args: str | Path, cwd: Path) -> subprocess.CompletedProcess[str]:
    # without PYTHONPATH, so that nothing but the installed wheel can provide btplan
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run(
        [str(a) for a in args], cwd=cwd, capture_output=True, text=True, check=False, env=env
    )


def borrow_dependencies(python: Path) -> None:
    """Let the new venv import what the suite's own interpreter has installed.

    A plain path in a .pth file is appended to sys.path after the venv's own site-packages,
    and the .pth files inside it are not processed, so the checkout's editable install
    cannot shadow the wheel.
    """
    where = run(python, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])",
                cwd=python.parent)
    assert where.returncode == 0, where.stderr
    own = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"]}
    (Path(where.stdout.strip()) / "borrowed.pth").write_text("\n".join(sorted(own)) + "\n")


@pytest.mark.slow
def test_installed_wheel_reads_both_grammars(tmp_path: Path) -> None:
    source = tmp_path / "src"
    source.mkdir()
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, source / name)
    for folder in ("btplan", "grammar", "domains"):
        shutil.copytree(
            ROOT / folder, source / folder, ignore=shutil.ignore_patterns("__pycache__")
        )
    wheels = tmp_path / "wheels"
    built = run(
        sys.executable,
        "-m",
        "pip",
        "wheel",
        "--no-deps",
        "--no-build-isolation",
        "-q",
        "-w",
        wheels,
        source,
        cwd=tmp_path,
    )
    assert built.returncode == 0, built.stderr
    assert "warning" not in (built.stdout + built.stderr).lower(), built.stderr
    (wheel,) = wheels.glob("btplan-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "btplan/grammar/btplan.lark" in names and "btplan/grammar/pddl.lark" in names
    assert "btplan/domains/pick_place.bt" in names and "btplan/domains/scenes/youbot.toml" in names
    assert {"btplan/monitor/web/view.html", "btplan/monitor/web/view.js",
            "btplan/monitor/web/view.css"} <= set(names)
    packages = {str(init.parent.relative_to(ROOT)) for init in (ROOT / "btplan").rglob("__init__.py")}
    assert {f"{package}/__init__.py" for package in packages} <= set(names)  # none left out
    metadata = zipfile.ZipFile(wheel).read("btplan-0.1.0.dist-info/METADATA").decode()
    assert "License-Expression: MIT" in metadata

    venv = tmp_path / "venv"
    made = run(sys.executable, "-m", "venv", venv, cwd=tmp_path)
    assert made.returncode == 0, made.stderr
    python = venv / "bin" / "python"
    borrow_dependencies(python)
    installed = run(python, "-m", "pip", "install", "-q", "--no-deps", wheel, cwd=tmp_path)
    assert installed.returncode == 0, installed.stderr
    # pip's own complaint about a package index of the machine's pip configuration is
    # not about the wheel
    about_the_wheel = [line for line in installed.stderr.splitlines()
                       if "is ignored: it is neither a file nor a directory" not in line]
    assert "warning" not in "\n".join(about_the_wheel).lower(), installed.stderr

    work = tmp_path / "elsewhere"
    work.mkdir()
    shutil.copy(ROOT / "domains" / "pick_place.bt", work / "pick_place.bt")
    script = (
        "import btplan, btplan.lang as lang\n"
        "from btplan.lang.generators import generate\n"
        "print(btplan.__file__)\n"
        "print(lang.load(['pick_place.bt']).problem.name)\n"
        "open('d.pddl', 'w').write(generate('gripper', balls=2)[0])\n"
        "open('p.pddl', 'w').write(generate('gripper', balls=2)[1])\n"
        "print(lang.load(['d.pddl', 'p.pddl']).problem.name)\n"
    )
    checked = run(python, "-c", script, cwd=work)
    assert checked.returncode == 0, checked.stderr
    where, bt_problem, pddl_problem = checked.stdout.split()
    assert Path(where).is_relative_to(venv) and bt_problem == "cube_on_goal"
    assert pddl_problem == "gripper_2_s0"

    command = run(venv / "bin" / "btplan", "check", "pick_place.bt", "d.pddl", "p.pddl", cwd=work)
    assert command.returncode == 0, command.stderr
    assert "problem cube_on_goal for pick_place" in command.stdout

    version = run(venv / "bin" / "btplan", "--version", cwd=work)
    assert version.returncode == 0 and version.stdout == "btplan 0.1.0\n", version.stderr
    module = run(python, "-m", "btplan", "--version", cwd=work)
    assert module.stdout == version.stdout, module.stderr

    # a shipped domain by name, from a folder without it: read from the installed package
    planned = run(venv / "bin" / "btplan", "plan", "pick_place_obstacle", "-f", "json",
                  "-o", "tree.json", "--plan-out", "sas_plan", cwd=work)
    assert planned.returncode == 0, planned.stderr
    assert not (work / "pick_place_obstacle.bt").exists()
    assert json.loads((work / "tree.json").read_text())["root"]["type"] == "Fallback"
    *steps, cost = (work / "sas_plan").read_text().splitlines()
    assert steps[-1] == "(place cube goal)" and cost == f"; cost = {len(steps)} (unit cost)"
    where = run(python, "-c", "from btplan import shipped; print(shipped.folder())", cwd=work)
    assert Path(where.stdout.strip()).is_relative_to(venv)
