"""The examples of the documentation run as written, and say what the page shows.

Every `sh`, `console` and `python` block of every page under docs/ (its subfolders
included) is run from a fresh folder that holds the shipped domains and examples:

- shell lines one by one, in page order (exit 0);
- a `console` block's `$ ` lines the same way, each followed by the output the page
  shows, which must match what the command prints (standard output and error together;
  a line `...` stands for any lines, and `...` inside a line for any text, so that times
  and paths may vary; a command whose shown output starts with `error:` must exit 2, as
  bad input does);
- each page's Python blocks in one interpreter, in order, as a reader pastes them; an
  `output` block right after a Python block shows what that block prints, and must
  match it the same way.

What is not run is listed below with the reason, and is run elsewhere where it can be.
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
BLOCK = re.compile(r"^( *)```(\w*)\n(.*?)^\1```", re.MULTILINE | re.DOTALL)
MARK = "--- end of a block of the page ---"
"""Printed between a page's Python blocks, to tell what each of them printed."""

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
    "python -m pytest": "the test suite itself, which these tests are part of",
    "HYPOTHESIS_PROFILE=long": "searches for many minutes (the suite runs the short profile)",
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

PAGES = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
"""Every page, those under docs/reference/ and the other folders too, by its path in docs/."""


def all_blocks(page: str) -> list[tuple[str, str]]:
    """The page's runnable blocks in page order, as (language, body), indents removed."""
    found = []
    for indent, kind, body in BLOCK.findall((DOCS / page).read_text()):
        lines = [line[len(indent):] if line.startswith(indent) else line.lstrip()
                 for line in body.splitlines()]
        found.append((kind, "\n".join(lines) + "\n"))
    return found


def blocks(page: str, language: str) -> list[str]:
    return [body for kind, body in all_blocks(page) if kind == language]


def sessions(body: str) -> list[tuple[str, list[str]]]:
    """A console block's commands, each with the output lines the page shows after it."""
    shown: list[tuple[str, list[str]]] = []
    lines = body.splitlines()
    index = 0
    while index < len(lines):
        line = lines[index]
        if not line.startswith("$ "):
            raise AssertionError(f"console block: output before any command: {line!r}")
        command = line[2:]
        while command.endswith("\\") and index + 1 < len(lines):
            index += 1
            command = command[:-1].rstrip() + " " + lines[index].strip()
        index += 1
        output = []
        while index < len(lines) and not lines[index].startswith("$ "):
            output.append(lines[index])
            index += 1
        shown.append((command.split("  #")[0].strip(), output))
    return shown


def line_pattern(line: str) -> str:
    return ".*".join(re.escape(part) for part in line.rstrip().split("..."))


def output_matches(shown: list[str], printed: str) -> bool:
    """Whether the printed text is what the page shows, `...` standing for what varies."""
    pattern = []
    for line in shown:
        pattern.append(r"(?:.*\n)*?" if line.strip() == "..." else line_pattern(line) + r"[ \t]*\n")
    text = "".join(line.rstrip() + "\n" for line in printed.splitlines())
    return re.fullmatch("".join(pattern), text) is not None


def commands(body: str) -> list[str]:
    """Shell lines, continuations joined, comments and blank lines dropped."""
    joined = re.sub(r"\\\n\s*", " ", body)
    return [line.split("  #")[0].strip() for line in joined.splitlines()
            if line.strip() and not line.strip().startswith("#")]


@pytest.fixture
def folder(tmp_path: Path) -> Path:
    for name in ("domains", "examples", "tests/bt/corpus"):
        shutil.copytree(ROOT / name, tmp_path / name)
    return tmp_path


def environment() -> dict[str, str]:
    return {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}


def run_line(page: str, line: str, folder: Path, exit_code: int = 0) -> str:
    """Runs one shell line of the page as a reader would, and returns what it printed."""
    done = subprocess.run(["bash", "-o", "pipefail", "-c", line], cwd=folder,
                          env=environment(), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=600)
    assert done.returncode == exit_code, f"{page}: {line}\n{done.stdout[-2000:]}"
    return done.stdout


def expected_exit(shown: list[str]) -> int:
    """0, or 2 (bad input) when the page shows the command's error line."""
    return 2 if shown and shown[0].startswith("error:") else 0


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "sh") or blocks(p, "console")])
def test_the_shell_examples_run(page: str, folder: Path) -> None:
    ran = 0
    for kind, body in all_blocks(page):
        if kind == "console":
            for line, shown in sessions(body):
                if any(part in line for part in NOT_RUN):
                    continue
                printed = run_line(page, line, folder, expected_exit(shown))
                assert output_matches(shown, printed), (
                    f"{page}: {line}\nthe page shows:\n" + "\n".join(shown)
                    + f"\nit printed:\n{printed}")
                ran += 1
            continue
        if kind != "sh":
            continue
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
                run_line(page, line, folder)
            ran += 1
    if page not in ("reactivity.md", "ros.md", "pybullet.md") and not page.startswith(
            ("design/", "results/")):  # their commands are benchmarks, run by hand
        assert ran, f"{page}: no example ran"


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "python")
                                  and p not in PYTHON_NOT_RUN])
def test_the_python_examples_run(page: str, folder: Path) -> None:
    found = all_blocks(page)
    python = [index for index, (kind, _) in enumerate(found) if kind == "python"]
    script = f"\nprint({MARK!r})\n".join(found[index][1] for index in python)
    done = subprocess.run([sys.executable, "-c", script], cwd=folder, env=environment(),
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, f"{page}\n{done.stderr[-3000:]}"
    printed = done.stdout.split(MARK + "\n")
    for block, index in enumerate(python):
        after = found[index + 1] if index + 1 < len(found) else ("", "")
        if after[0] == "output":
            shown = after[1].splitlines()
            assert output_matches(shown, printed[block]), (
                f"{page}: Python block {block + 1}\nthe page shows:\n{after[1]}"
                f"it printed:\n{printed[block]}")


def test_every_output_block_follows_a_python_block() -> None:
    for page in PAGES:
        found = all_blocks(page)
        for index, (kind, _) in enumerate(found):
            if kind == "output":
                assert index and found[index - 1][0] == "python", (
                    f"{page}: an output block must come right after the Python block it shows")


@pytest.mark.parametrize(("shown", "printed", "matches"), [
    (["a", "b"], "a\nb\n", True),
    (["a", "b"], "a\nc\n", False),
    (["a"], "a\nb\n", False),
    (["a", "..."], "a\nb\nc\n", True),
    (["...", "c"], "a\nb\nc\n", True),
    (["took ... s"], "took 0.004 s\n", True),
    (["took ... s"], "took 0.004 ms\n", False),
    ([], "", True),
    ([], "something\n", False),
])
def test_the_shown_output_is_compared_with_what_varies_left_out(
        shown: list[str], printed: str, matches: bool) -> None:
    assert output_matches(shown, printed) is matches


def test_a_console_block_pairs_each_command_with_its_output() -> None:
    body = "$ btplan plan x \\\n    -q\nplanned\n$ cat plan.txt  # the plan\n(pick)\n"
    assert sessions(body) == [("btplan plan x -q", ["planned"]), ("cat plan.txt", ["(pick)"])]


RUN = {"sh", "console", "python"}
SHOWN = {
    "output": "what the Python block before it prints (checked with that block)",
    "bt": "an excerpt of a shipped .bt file (checked below)",
    "json": "JSON a command writes or reads (checked to parse)",
    "toml": "a binding or scene file (checked to parse)",
    "xml": "a tree file (checked to parse)",
    "cpp": "C++ for BehaviorTree.CPP (built by tests/bt when a compiler is present)",
    "text": "a synopsis, a sketch or a grammar: not code",
}
"""The languages a block may have besides those that run, and how each is kept true."""


def test_every_block_says_what_it_is() -> None:
    unlabelled = {page: sorted({kind for kind, _ in all_blocks(page)} - RUN - set(SHOWN))
                  for page in PAGES}
    assert {page: kinds for page, kinds in unlabelled.items() if kinds} == {}


def tokens(text: str) -> list[str]:
    """A .bt text's words and signs, comments and layout dropped."""
    return re.findall(r"\w+|[^\w\s]", re.sub(r"#[^\n]*", "", text))


def contains(words: list[str], part: list[str]) -> bool:
    width = len(part)
    return any(words[start:start + width] == part for start in range(len(words) - width + 1))


def test_the_bt_excerpts_are_taken_from_shipped_files() -> None:
    shipped = [tokens(path.read_text()) for path in (ROOT / "domains").rglob("*.bt")]
    shipped += [tokens(path.read_text()) for path in (ROOT / "examples").rglob("*.bt")]
    stale = [(page, body.splitlines()[0]) for page in PAGES
             for kind, body in all_blocks(page) if kind == "bt"
             if not any(contains(words, tokens(body)) for words in shipped)]
    assert stale == []


def test_the_files_shown_parse() -> None:
    import json
    import tomllib
    import xml.etree.ElementTree as ElementTree

    def xml_excerpt(text: str) -> object:
        """Elements one after another, `...` lines standing for the ones left out."""
        kept = "\n".join(line for line in text.splitlines()
                          if line.strip() != "..." and not line.startswith("<?xml"))
        return ElementTree.fromstring(f"<excerpt>{kept}</excerpt>")

    def json_excerpt(text: str) -> object:
        """JSON, `, ...` standing for the items left out of a list."""
        return json.loads(re.sub(r",\s*\.\.\.", "", text))

    readers = {"json": json_excerpt, "toml": tomllib.loads, "xml": xml_excerpt}
    for page in PAGES:
        for kind, body in all_blocks(page):
            if kind in readers:
                try:
                    readers[kind](body)
                except Exception as error:  # noqa: BLE001 - any reader's complaint
                    raise AssertionError(f"{page}: a {kind} block does not parse: {error}\n"
                                         f"{body[:300]}") from error


def test_the_files_the_pages_name_exist() -> None:
    """A page that points at a test, a benchmark or an example names a file that is there."""
    named = re.compile(r"\b((?:tests|bench|examples|domains|btplan)/[\w/.-]*\.(?:py|bt|pddl|dist|toml))")
    missing = sorted({(page, name) for page in PAGES
                      for name in named.findall((DOCS / page).read_text())
                      if not (ROOT / name).exists()})
    assert missing == []
