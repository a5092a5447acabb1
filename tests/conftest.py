"""Suite-wide options and checks.

`--update-golden` rewrites golden files instead of comparing. At the end of a run inside
a venv, every imported module must come from the venv, the checkout, the standard library
or a temporary folder: a module found in the machine's global site-packages would make
the suite pass here and fail on a fresh machine.
"""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

GOLDEN = Path(__file__).parent / "golden"


def pytest_sessionfinish(session: pytest.Session, exitstatus: int) -> None:
    if sys.prefix == sys.base_prefix:
        return  # not in a venv: nothing to compare with
    from test_environment import foreign_modules  # tests/ is on sys.path (rootdir conftest)

    foreign = foreign_modules()
    if foreign:
        reporter = session.config.pluginmanager.get_plugin("terminalreporter")
        if reporter is not None:
            reporter.write_line(
                "modules imported from outside the venv and the checkout "
                f"(install them through pyproject.toml): {', '.join(foreign)}", red=True)
        session.exitstatus = pytest.ExitCode.TESTS_FAILED


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption(
        "--update-golden",
        action="store_true",
        default=False,
        help="rewrite the files in tests/golden/ from the current output (review the diff!)",
    )


@pytest.fixture
def golden(request: pytest.FixtureRequest):  # type: ignore[no-untyped-def]
    """Compare text with tests/golden/NAME, or rewrite it under --update-golden."""
    update = request.config.getoption("--update-golden")

    def check(name: str, text: str) -> None:
        path = GOLDEN / name
        if update:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
            return
        assert path.exists(), f"missing golden file {name}; run pytest --update-golden"
        assert text == path.read_text(encoding="utf-8")

    return check
