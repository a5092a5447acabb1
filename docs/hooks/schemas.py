"""MkDocs hook: the JSON Schemas of btplan's file formats, from what defines them.

`<!-- schema tree -->` becomes the schema of saved trees, generated from their pydantic
models (`btplan export json --schema` prints the same text); `<!-- schema FILE.json -->`
becomes a schema file beside the page, such as the trace's, which is written by hand
because trace lines are plain dictionaries, and which tests/test_format_schemas.py
checks against real traces. Either way the page shows the schema the tests hold btplan
to.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

MARKER = re.compile(r"<!-- schema ([\w.-]+) -->")


def on_page_markdown(markdown: str, page: Any, config: Any, **_: Any) -> str:
    if "<!-- schema " not in markdown:
        return markdown
    folder = Path(config["docs_dir"]) / Path(page.file.src_path).parent
    return MARKER.sub(lambda found: fenced(schema(found.group(1), folder)), markdown)


def schema(name: str, folder: Path) -> str:
    """The schema `name` stands for; an unknown name or a missing file fails the build."""
    if name == "tree":
        from btplan.bt.formats import json_schema

        return json_schema()
    return (folder / name).read_text(encoding="utf-8")


def fenced(text: str) -> str:
    return f"```json\n{text.rstrip()}\n```"
