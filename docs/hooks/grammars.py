"""MkDocs hook: the grammars of the `.bt` language and of PDDL, as btplan reads them.

A page holds a marker such as `<!-- grammar btplan.lark -->`; at build time it is
replaced by that grammar, verbatim, read from the package data the readers load their
parsers from (btplan.lang.bt_reader.GRAMMAR_PACKAGE, through importlib.resources), so
the reference shows the grammar of the installed btplan, not a copy that could age.
"""

from __future__ import annotations

import re
from typing import Any

MARKER = re.compile(r"<!-- grammar ([\w.-]+\.lark) -->")


def on_page_markdown(markdown: str, page: Any, **_: Any) -> str:
    if "<!-- grammar " not in markdown:
        return markdown
    return MARKER.sub(lambda found: fenced(grammar(found.group(1))), markdown)


def grammar(name: str) -> str:
    """The text of a shipped grammar file; an unknown name fails the build."""
    from importlib.resources import files

    from btplan.lang.bt_reader import GRAMMAR_PACKAGE

    return files(GRAMMAR_PACKAGE).joinpath(name).read_text(encoding="utf-8")


def fenced(text: str) -> str:
    """A code block that holds `text` unchanged (no markup in a grammar is read)."""
    return f"```text\n{text.rstrip()}\n```"
