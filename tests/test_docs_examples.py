"""The examples of the documentation run as written.

Every `sh` and `python` block of every page under docs/ is run from a fresh folder that
holds the shipped domains and examples: shell lines one by one (exit 0), each page's
Python blocks in one interpreter, in order, as a reader pastes them (exit 0). What is not
run is listed below with the reason, and is run elsewhere where it can be.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
BLOCK = re.compile(r"^( *)```(sh|python)\n(.*?)^\1```", re.MULTILINE | re.DOTALL)

NOT_RUN = {
    "pip install": "installs packages: the suite runs in the installed environment",
    "python3 -m venv": "the install: the suite runs in it",
    "--install-completion": "changes the user's shell",
    "--show-completion": "changes the user's shell",
    "| dot ": "needs graphviz, which pip does not install (tests/bt/test_dot_ascii.py)",
    "domain.pddl problem.pddl": "placeholder file names",
    "--seeds 0:1000": "a sweep of hours (bench/reactivity.py)",
    "--seeds 0:300": "a sweep of minutes, recorded with its results (docs/results/reactivity.md)",
    "--sim pybullet": "minutes in the simulator (tests/worlds, marked slow)",
    "python bench/": "benchmarks, minutes to hours",
    "fake_robot.py": "a second terminal (tests/ros runs it)",
    "--ros ": "needs the robot of the second terminal (tests/ros)",
    "--ray ": "needs a Ray cluster",
    "--hz 2": "a live view at two ticks a second (the same run without it is run)",
    "--groot": "serves Groot2 until the run ends (tests/monitor)",
    "--view": "serves a browser view (tests/monitor)",
}
"""Shell lines not run: a part of the line -> why."""

PYTHON_NOT_RUN = {
    "trees.md": "fragments: the World protocol's shape and a recorder on a tree of the page",
    "pybullet.md": "minutes in the simulator (tests/worlds, marked slow)",
    "language.md": "placeholder file names and text",
    "monitor.md": "serves Groot2 on its default port (tests/monitor runs the same)",
}
"""Pages whose Python blocks are not run, and why."""

PAGES = sorted(p.name for p in DOCS.glob("*.md"))


def blocks(page: str, language: str) -> list[str]:
    return [body for _, kind, body in BLOCK.findall((DOCS / page).read_text()) if kind == language]


def commands(body: str) -> list[str]:
    """Shell lines, continuations joined, comments and blank lines dropped."""
    joined = re.sub(r"\\\n\s*", " ", body)
    return [line.split("  #")[0].strip() for line in joined.splitlines()
            if line.strip() and not line.strip().startswith("#")]


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    for name in ("domains", "examples"):
        shutil.copytree(ROOT / name, tmp_path / name)
    return tmp_path


def environment() -> dict[str, str]:
    return {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "sh")])
def test_the_shell_examples_run(page: str, folder: Path) -> None:
    ran = 0
    for body in blocks(page, "sh"):
        for line in commands(body):
            if any(part in line for part in NOT_RUN):
                continue
            if line.startswith("btplan view"):
                serving = subprocess.Popen(["bash", "-c", f"exec {line} --port 0"], cwd=folder,
                                           env=environment(), stderr=subprocess.PIPE, text=True)
                assert serving.stderr is not None
                said = serving.stderr.readline()
                serving.send_signal(signal.SIGINT)
                serving.wait(timeout=30)
                assert "at http://127.0.0.1:" in said, said
            else:
                done = subprocess.run(["bash", "-o", "pipefail", "-c", line], cwd=folder,
                                      env=environment(), capture_output=True, text=True,
                                      timeout=600)
                assert done.returncode == 0, f"{page}: {line}\n{done.stderr[-2000:]}"
            ran += 1
    if page not in ("reactivity.md", "ros.md", "pybullet.md"):
        assert ran, f"{page}: no example ran"


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "python")
                                  and p not in PYTHON_NOT_RUN])
def test_the_python_examples_run(page: str, folder: Path) -> None:
    script = "\n\n".join(blocks(page, "python"))
    done = subprocess.run([sys.executable, "-c", script], cwd=folder, env=environment(),
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"{page}\n{done.stderr[-3000:]}"
