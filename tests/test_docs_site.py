"""The documentation site builds strictly (its examples run in test_docs_examples.py)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


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
    pages = {name: (tmp_path / "site" / "reference" / name / "index.html").read_text()
             for name in ("grammar", "trace", "tree-json")}
    assert "start: unit*" in pages["grammar"]  # the grammars, included from the package
    assert "LPAR: &quot;(&quot;" in pages["grammar"]
    assert "&quot;$schema&quot;" in pages["trace"]  # the schema and a line of a real run
    assert "&quot;tick&quot;: 5" in pages["trace"]
    assert "&quot;title&quot;: &quot;SavedTree&quot;" in pages["tree-json"]  # from the model
    assert "&quot;format&quot;: &quot;btplan-tree&quot;" in pages["tree-json"]
    for page in pages.values():  # every marker replaced (the theme's own comments aside)
        assert "<!--" not in page.split('role="main"')[1].split("<!-- Copyright")[0]
