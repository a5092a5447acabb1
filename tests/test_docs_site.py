"""The documentation site builds strictly, and the shell examples of its getting-started
and concepts pages run as written (exit 0), from a fresh folder with the shipped domains
and examples."""

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
RUN_PAGES = ["getting-started.md", "concepts.md"]
BLOCK = re.compile(r"^( *)```sh\n(.*?)^\1```", re.MULTILINE | re.DOTALL)


def test_the_site_builds_strictly(tmp_path: Path) -> None:
    """A warning, a broken link or anchor, a page left out of the nav, or an API name
    that is not there fails the build."""
    built = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-d",
                            str(tmp_path / "site")], cwd=ROOT, capture_output=True, text=True,
                           timeout=600)
    assert built.returncode == 0, built.stderr
    commands = (tmp_path / "site" / "reference" / "commands" / "index.html").read_text()
    for command in ("check", "plan", "run", "export", "generate-blocksworld", "sweep", "view"):
        assert f'id="btplan-{command}"' in commands  # generated from the app itself
    assert "--ros" in commands and "--groot" in commands


def shell_lines(page: str) -> list[str]:
    text = (ROOT / "docs" / page).read_text()
    return [line.strip() for _, block in BLOCK.findall(text) for line in block.splitlines()
            if line.strip() and not line.strip().startswith("#")]


@pytest.mark.parametrize("page", RUN_PAGES)
def test_the_shell_examples_run(page: str, tmp_path: Path) -> None:
    for folder in ("domains", "examples"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    lines = shell_lines(page)
    assert lines
    for line in lines:
        if line.startswith("python3 -m venv"):
            continue  # the install: the suite runs in it
        if line.startswith("btplan view"):
            serving = subprocess.Popen(["bash", "-c", f"exec {line} --port 0"], cwd=tmp_path,
                                       env=env, stderr=subprocess.PIPE, text=True)
            assert serving.stderr is not None
            said = serving.stderr.readline()
            serving.send_signal(signal.SIGINT)
            serving.wait(timeout=30)
            assert "at http://127.0.0.1:" in said, said
            continue
        done = subprocess.run(["bash", "-c", line], cwd=tmp_path, env=env,
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, f"{line}\n{done.stderr}"
