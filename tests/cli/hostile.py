"""Shared by the hostile-input tests: the CLI run in-process, and what a clean failure is.

The Hypothesis budget comes from a profile chosen by HYPOTHESIS_PROFILE: `ci` (the
default) is small and derandomized so every CI run tries the same inputs; `long` is
for a search on demand (docs/reliability.md):

    HYPOTHESIS_PROFILE=long python -m pytest tests/cli/test_hostile_fuzz.py
"""

from __future__ import annotations

import os
import re
import sys
from dataclasses import dataclass
from datetime import timedelta
from functools import cache
from pathlib import Path
from typing import Any

import typer
import typer.main
from hypothesis import HealthCheck, settings
from typer.testing import CliRunner

from btplan.cli import app
from btplan.limits import EXCERPT_WIDTH, MAX_MESSAGE

ROOT = Path(__file__).resolve().parents[2]
DOMAINS = ROOT / "domains"
GOLDEN = ROOT / "tests" / "golden"
PICK_PLACE = str(DOMAINS / "pick_place.bt")
YOUBOT = str(DOMAINS / "youbot.bt")

settings.register_profile(
    "ci", max_examples=40, derandomize=True, database=None, deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
"""Inputs are bounded (a few tens of KB), so a hang shows as a test that never ends."""
settings.register_profile(
    "long", max_examples=1000, deadline=timedelta(seconds=10),
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
"""On demand: more and fresh examples, and a deadline that flags a super-linear reader."""

PROFILE = settings.get_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def budget(share: float = 1.0) -> settings:
    """The active profile with `share` of its examples (slow readers get fewer)."""
    return settings(PROFILE, max_examples=max(1, round(PROFILE.max_examples * share)))


runner = CliRunner()


@dataclass(frozen=True)
class Outcome:
    """What one in-process run of the CLI printed and how it ended."""

    exit_code: int
    stdout: str
    stderr: str
    exception: BaseException | None

    @property
    def output(self) -> str:
        return self.stdout + self.stderr


@cache
def _command() -> Any:
    """Built once: typer rebuilds the click command on every CliRunner.invoke, which
    would cost more than most of the runs under test."""
    return typer.main.get_command(app)

LONGEST_MESSAGE = 2 * MAX_MESSAGE + 200
"""A message and its hint, with room for `error: `, the file's path, line and column."""
_MESSAGE = re.compile(r"^(error|failed|warning): ")


def invoke(args: list[str], stdin: str | bytes | None = None) -> Outcome:
    """The `btplan` entry point run in-process, as CliRunner does, with streams captured."""
    exception: BaseException | None = None
    with runner.isolation(input=stdin) as (out, err, _):
        try:
            _command().main(args=args, prog_name="btplan")
            code = 0
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else int(stop.code is not None)
        except Exception as error:  # a traceback: what the tests exist to catch
            code, exception = 1, error
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
        stdout, stderr = out.getvalue(), err.getvalue()
    return Outcome(code, stdout.decode("utf-8", "replace"), stderr.decode("utf-8", "replace"),
                   exception)


def assert_clean(result: Outcome) -> None:
    """Exit 0, 1 or 2; never a traceback; on failure, messages and short excerpts only."""
    detail = f"exit {result.exit_code}\n{result.output}\n{result.exception!r}"
    assert result.exception is None, detail
    assert result.exit_code in (0, 1, 2), detail
    assert "Traceback" not in result.stderr, detail
    lines = result.stderr.splitlines()
    if result.exit_code == 2:
        assert any(line.startswith("error: ") for line in lines), detail
    if result.exit_code == 1:
        assert any(line.startswith(("failed: ", "error: ")) for line in lines), detail
    for line in lines:
        if _MESSAGE.match(line):
            assert len(line) <= LONGEST_MESSAGE, detail
        elif line.startswith("  "):
            # an excerpt of the offending line ('...' marks a cut at either end) or a caret
            assert len(line) <= 2 + EXCERPT_WIDTH + 6, detail


def error_lines(result: Outcome) -> list[str]:
    return [line for line in result.stderr.splitlines() if line.startswith("error: ")]
