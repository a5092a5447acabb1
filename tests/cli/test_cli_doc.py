"""docs/cli.md and `--help` agree: every command, argument and option, in both directions.

The page is split at its `## \\`btplan NAME\\`` headings. For each command the usage line
of `--help` must appear in its section; every option of the command (with its metavar)
must appear in the section's tables; and every flag the tables mention must exist.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest
import typer.main
from typer.testing import CliRunner

from btplan.cli import app

PAGE = Path(__file__).resolve().parents[2] / "docs" / "cli.md"
FLAG = re.compile(r"(?<![\w-])(--?[a-zA-Z][\w-]*)")
runner = CliRunner()
GROUP: Any = typer.main.get_command(app)
SECTIONS = {
    "check": [["check"]],
    "plan": [["plan"]],
    "run": [["run"]],
    "export": [["export"]],
    "sweep": [["sweep"]],
    "view": [["view"]],
    "generate": [["generate", "blocksworld"], ["generate", "gripper"], ["generate", "logistics"],
                 ["generate", "assembly"]],
}


def section(name: str) -> str:
    text = PAGE.read_text(encoding="utf-8")
    start = text.index(f"## `btplan {name}`")
    end = text.find("\n## ", start + 1)
    return text[start:end if end != -1 else len(text)]


def global_section() -> str:
    text = PAGE.read_text(encoding="utf-8")
    start = text.index("### Global options")
    return text[start:text.index("\n### ", start + 1)]


def table_text(text: str) -> str:
    return "\n".join(line for line in text.splitlines() if line.startswith("| "))


def command(path: list[str]) -> Any:
    found = GROUP
    for name in path:
        found = found.commands[name]
    return found


def options(cmd: Any) -> dict[str, str | None]:
    """Each visible option's names (but -h/--help) -> its metavar."""
    shown: dict[str, str | None] = {}
    for param in cmd.params:
        if param.param_type_name != "option" or param.hidden:
            continue
        for name in [*param.opts, *param.secondary_opts]:
            shown[name] = param.metavar
    return shown


def usage(path: list[str]) -> str:
    result = runner.invoke(app, [*path, "--help"], env={"COLUMNS": "200"})
    match = re.search(r"Usage: (.*?)\s*$", result.stdout, re.MULTILINE)
    assert match, result.stdout
    return match.group(1)


@pytest.mark.parametrize("name", sorted(SECTIONS))
def test_each_command_section_matches_its_help(name: str) -> None:
    text = section(name)
    tables = table_text(text)
    mentioned = set(FLAG.findall(tables))
    known: set[str] = set()
    for path in SECTIONS[name]:
        assert usage(path) in text, f"the usage line of {' '.join(path)} is not on the page"
        for flag, metavar in options(command(path)).items():
            known.add(flag)
            assert flag in mentioned, f"{' '.join(path)} {flag} is not documented"
            if metavar and flag.startswith("--"):
                assert f"{flag} {metavar}" in tables, f"{flag} is not shown with {metavar}"
    assert mentioned <= known, f"documented but not in --help: {sorted(mentioned - known)}"


def test_the_global_options_match() -> None:
    mentioned = set(FLAG.findall(table_text(global_section())))
    assert mentioned == set(options(GROUP))


def test_every_command_has_a_section() -> None:
    listed = {name for name in GROUP.commands}
    assert listed == set(SECTIONS)
    synopsis = PAGE.read_text(encoding="utf-8").split("```")[1]
    for name in listed:
        assert f"btplan {name}" in synopsis


def test_a_missing_option_is_caught(monkeypatch: pytest.MonkeyPatch) -> None:
    """Guard against a check that passes on any page."""
    original = PAGE.read_text(encoding="utf-8")
    trimmed = original.replace("| `--paper` |", "| `paper` |")
    assert trimmed != original
    monkeypatch.setattr(Path, "read_text", lambda self, encoding=None: trimmed)
    with pytest.raises(AssertionError, match="--paper is not documented"):
        test_each_command_section_matches_its_help("plan")
