"""MkDocs hook: what a btplan command prints, run when the site is built.

`<!-- output: btplan ARGS -->` becomes the standard output of `btplan ARGS`, run from
the repository's root (where domains/ and examples/ are); `<!-- output line N: btplan
ARGS -->` keeps its Nth line only. JSON output is shown as JSON, a long JSON line
spread over several lines with its values unchanged, so an example of a file format on
a page is the format as btplan writes it today. A command that fails fails the build.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

MARKER = re.compile(r"<!-- output(?: line (\d+))?: btplan (.+?) -->")
WIDTH = 88
"""Characters a line of a spread JSON value may take before it is broken."""


def on_page_markdown(markdown: str, page: Any, config: Any, **_: Any) -> str:
    if "<!-- output" not in markdown:
        return markdown
    root = Path(config["config_file_path"]).parent

    def replace(found: re.Match[str]) -> str:
        text = run(found.group(2), root)
        if found.group(1) is not None:
            text = text.splitlines()[int(found.group(1)) - 1]
        return shown(text)

    return MARKER.sub(replace, markdown)


def run(arguments: str, root: Path) -> str:
    """The standard output of `btplan ARGUMENTS`, with the btplan of this checkout."""
    path = os.pathsep.join(p for p in (str(root), os.environ.get("PYTHONPATH")) if p)
    done = subprocess.run([sys.executable, "-m", "btplan", *shlex.split(arguments)],
                          cwd=root, env={**os.environ, "PYTHONPATH": path},
                          capture_output=True, text=True, timeout=300, check=False)
    if done.returncode != 0:
        raise RuntimeError(f"btplan {arguments} failed ({done.returncode}): {done.stderr}")
    return done.stdout


def shown(text: str) -> str:
    """A code block: JSON as JSON (one long line spread out), anything else as text."""
    try:
        value = json.loads(text)
    except ValueError:
        return f"```text\n{text.rstrip()}\n```"
    if "\n" not in text.strip() and isinstance(value, dict):
        text = spread(value)
    return f"```json\n{text.rstrip()}\n```"


def spread(value: dict[str, Any]) -> str:
    """One key a line; a list too long for one line gets as many items a line as fit."""
    lines = ["{"]
    for n, (key, item) in enumerate(value.items()):
        comma = "," if n < len(value) - 1 else ""
        head = f"  {json.dumps(key)}: "
        one = json.dumps(item, ensure_ascii=False)
        if not isinstance(item, list) or len(head) + len(one) <= WIDTH or not item:
            lines.append(head + one + comma)
            continue
        lines.append(head + "[")
        lines += [f"    {row}" for row in _rows([json.dumps(i, ensure_ascii=False)
                                                  for i in item])]
        lines.append("  ]" + comma)
    lines.append("}")
    return "\n".join(lines)


def _rows(items: list[str]) -> list[str]:
    """Items joined by commas, greedily, into rows of at most WIDTH characters."""
    rows: list[str] = []
    row = ""
    for n, item in enumerate(items):
        piece = item + ("," if n < len(items) - 1 else "")
        if row and len(row) + 1 + len(piece) > WIDTH - 4:
            rows.append(row)
            row = piece
        else:
            row = f"{row} {piece}" if row else piece
    return [*rows, row]
