"""Find where a value sits in a JSON text, so errors about saved trees point at a line.

The standard `json` module reports positions only for syntax errors; pydantic reports
a path (`root.children.0.ident`). This small scanner walks the text along that path and
returns the 1-based line and column of the value (or of the object missing a key).
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from json.decoder import scanstring  # type: ignore[attr-defined]

_SPACE = re.compile(r"[ \t\n\r]*")
_SCALAR = re.compile(r"-?(?:0|[1-9]\d*)(?:\.\d+)?(?:[eE][-+]?\d+)?|true|false|null")


def _skip(text: str, i: int) -> int:
    match = _SPACE.match(text, i)
    return match.end() if match else i


def _end_of_value(text: str, i: int) -> int:
    """Index just past the JSON value starting at `i` (the text is known to be valid)."""
    _, end = json.JSONDecoder().raw_decode(text, i)
    return end


def _child(text: str, i: int, step: str | int) -> int | None:
    """Start index of member `step` of the object or array starting at `i`."""
    opener = text[i]
    i = _skip(text, i + 1)
    index = 0
    while i < len(text) and text[i] not in "]}":
        if opener == "{":
            key, i = scanstring(text, i + 1)
            i = _skip(text, _skip(text, i) + 1)  # past the colon
            if key == step:
                return i
        elif index == step:
            return i
        i = _skip(text, _end_of_value(text, i))
        index += 1
        if i < len(text) and text[i] == ",":
            i = _skip(text, i + 1)
    return None


def locate(text: str, path: Sequence[str | int]) -> tuple[int, int]:
    """Line and column of the deepest value along `path` that exists in `text`."""
    i = _skip(text, 0)
    for step in path:
        if i >= len(text) or text[i] not in "[{":
            break
        found = _child(text, i, step)
        if found is None:
            break
        i = found
    line = text.count("\n", 0, i) + 1
    return line, i - (text.rfind("\n", 0, i) + 1) + 1


def line_at(text: str, line: int) -> str:
    """Line `line` (1-based) of `text`, to quote under an error; an empty string when it is
    out of range, so a bad position never hides the error itself."""
    lines = text.splitlines()
    return lines[line - 1] if 0 < line <= len(lines) else ""


__all__ = ["line_at", "locate"]
