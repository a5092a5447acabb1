"""How much input btplan accepts, and how much of it an error message shows.

Every reader (.bt, PDDL, saved JSON trees, scene TOML, disturbance files and specs)
checks its input against these limits before parsing, so a hostile or corrupted file
ends in a located InputError (exit 2) instead of exhausting memory, time or Python's
recursion limit. The numbers sit far above anything btplan plans with in practice;
docs/reliability.md lists them with the tests that hold them.
"""

from __future__ import annotations

import operator
import re
from collections.abc import Iterator
from itertools import accumulate, repeat, takewhile

from btplan.errors import EXCERPT_WIDTH, InputError, Span, excerpt
from btplan.records import record

MAX_INPUT_BYTES = 8 * 1024 * 1024
"""Largest input file read, in bytes (8 MiB).

Shipped and generated domains are a few kilobytes; machine-made problems with thousands
of objects stay well under a megabyte. The bound keeps memory (the parsers hold about a
hundred bytes per token) and time bounded: dense .bt or PDDL parses at tens to hundreds
of KB per second (40-60 KB/s measured on a busy 2-core machine), so the largest input
takes minutes at worst, never forever; comments cost next to nothing. It also stops a
device such as /dev/zero or an endless pipe from being read forever.
"""

MAX_NESTING = 100
"""Deepest bracket nesting in .bt, PDDL and TOML text.

Real PDDL conditions nest about ten deep, .bt and scenes at most three. Checked with a
flat scan before parsing, because some parsers (tomllib) and every tree walk recurse,
and Python's recursion limit (1000 frames) must never be what stops a reader.
"""

MAX_TYPE_DEPTH = 100
"""Longest chain of types from a type up to the root of its hierarchy.

Real hierarchies are a handful of levels deep. Subtype checks walk the chain each time
they are asked, so a chain of 10,000 types declared in a flat list would make checking
a domain take hours.
"""

MAX_TREE_DEPTH = 100
"""Deepest behavior tree read from a file, in nodes from the root to a leaf.

Trees the planner builds for the shipped and generated domains are at most 16 deep.
Ticking, exporting and saving a tree are recursive (a few frames per level), so a
bound well under Python's recursion limit keeps every later step safe too.
"""

MAX_JSON_NESTING = 2 * MAX_TREE_DEPTH + 1
"""Deepest bracket nesting of a saved JSON tree: an object and a `children` array per
node, and one more for a leaf's `args`; checked before `json.loads`, which recurses."""

MAX_TICK = 999_999_999
"""Largest tick number in a disturbance spec or a scene event: a billion ticks is beyond
any run, and a bound keeps int() away from numbers of thousands of digits, which it
refuses with an error of its own."""

MAX_SCENE_MAGNITUDE = 10_000.0
"""Largest size of a number in a scene (metres, seconds, metres per second).

PyBullet computes in single precision, so far beyond this a position loses whole
centimetres, and products such as speed × tick duration must stay finite.
"""

MAX_SCENE_ITEMS = 1000
"""Most walls, cubes, regions or events (each) in a scene: PyBullet builds a body for
each thing, and every motion is checked against all of them; the shipped scene has a
handful."""

MAX_ECHO = 40
"""Characters of a name, key or value quoted back in an error message."""

MAX_MESSAGE = 200
"""Characters of a message, and of its hint, that the CLI prints. Only quoted input makes
one longer (a 3,000-character name); the middle is cut so that both ends still read."""


def shorten(text: str, width: int = MAX_ECHO) -> str:
    """`text` cut to `width` characters, marked with '...' when cut, for quoting in a message."""
    return text if len(text) <= width else text[: max(width - 3, 1)] + "..."


def printable(text: str) -> str:
    """`text` with its control characters written as escapes (`\\x1b`, `\\n`): a name or
    a path read from input must not drive the terminal, nor break a one-line message."""
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def abridge(text: str, width: int = MAX_MESSAGE) -> str:
    """`text` with its middle cut out when longer than `width`, so the end still reads."""
    if len(text) <= width:
        return text
    tail = width // 3
    return text[: width - tail - 5] + " ... " + text[-tail:]


def check_size(size: int, path: str) -> None:
    """Refuse an input of `size` bytes (or characters) above MAX_INPUT_BYTES."""
    if size > MAX_INPUT_BYTES:
        raise InputError(
            f"this input is larger than {MAX_INPUT_BYTES // (1024 * 1024)} MiB, "
            "the most btplan reads",
            Span(path, 1, 1),
            "split it, or check that it is the file you meant",
        )


@record(frozen=True, slots=True)
class Brackets:
    """What counts as nesting in one language: its brackets, and the text to skip.

    `skip` is a regular expression for strings and comments, whose brackets do not
    count; it is compiled when first used (a plan run reads one language of four).
    """

    opening: str
    closing: str
    skip: str | None = None


BT_BRACKETS = Brackets("({", ")}", r"#[^\n]*")
PDDL_BRACKETS = Brackets("(", ")", r";[^\n]*")
TOML_BRACKETS = Brackets(
    "[{", "]}", r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*')
"""TOML arrays and inline tables; strings of all four kinds and comments are skipped."""
JSON_BRACKETS = Brackets("[{", "]}", r'"(?:[^"\\]|\\.)*"')


def check_nesting(text: str, path: str, brackets: Brackets,
                  limit: int = MAX_NESTING, message: str | None = None) -> None:
    """Refuse text whose brackets nest deeper than `limit`, at the first one too deep.

    Depth is counted from the start of the text without recursion, in C-speed passes
    (about a second for MAX_INPUT_BYTES of brackets on a slow machine). A closing bracket
    with no opening one is the parser's to report: it fails there, before any depth.
    """
    body = re.sub(brackets.skip, "", text) if brackets.skip else text
    marks = _marks(body, brackets)
    if max(accumulate(_steps(marks)), default=0) <= limit:
        return
    count = len(list(takewhile(limit.__ge__, accumulate(_steps(marks)))))
    raise located(text, path, _index_of_bracket(text, brackets, count),
                  message or f"brackets nested more than {limit} levels deep",
                  "btplan reads no deeper; see 'Hostile input' in docs/reliability.md")


def _marks(body: str, brackets: Brackets) -> bytes:
    """The brackets of `body` alone, in order: 2 for an opening one, 0 for a closing one."""
    table: dict[int, str | None] = {ord(c): None for c in set(body)}
    table.update({ord(c): "\x02" for c in brackets.opening})
    table.update({ord(c): "\x00" for c in brackets.closing})
    return body.translate(table).encode("latin-1")


def _steps(marks: bytes) -> Iterator[int]:
    """+1 for each opening bracket, -1 for each closing one (C-speed: no Python loop)."""
    return map(operator.sub, marks, repeat(1))


def _index_of_bracket(text: str, brackets: Brackets, count: int) -> int:
    """Where in `text` the bracket number `count` (from 0, skipped text aside) is."""
    runs = f"[{re.escape(brackets.opening)}]+|[{re.escape(brackets.closing)}]+"
    pattern = re.compile(f"{brackets.skip}|{runs}" if brackets.skip else runs)
    seen = 0
    for match in pattern.finditer(text):
        run = match.group()
        if run[0] in brackets.opening or run[0] in brackets.closing:
            if seen + len(run) > count:
                return match.start() + count - seen
            seen += len(run)
    return 0


def located(text: str, path: str, index: int, message: str,
            hint: str | None = None) -> InputError:
    """An InputError at character `index` of `text`, with its line for the caret."""
    line = text.count("\n", 0, index) + 1
    start = text.rfind("\n", 0, index) + 1
    end = text.find("\n", index)
    source = text[start:] if end < 0 else text[start:end]
    return InputError(message, Span(path, line, index - start + 1), hint, source)


__all__ = [
    "BT_BRACKETS", "EXCERPT_WIDTH", "JSON_BRACKETS", "MAX_ECHO", "MAX_INPUT_BYTES",
    "MAX_JSON_NESTING", "MAX_MESSAGE", "MAX_NESTING", "MAX_SCENE_ITEMS", "MAX_SCENE_MAGNITUDE",
    "MAX_TICK", "MAX_TREE_DEPTH", "MAX_TYPE_DEPTH", "PDDL_BRACKETS", "TOML_BRACKETS",
    "Brackets", "abridge", "check_nesting", "check_size", "excerpt", "located", "shorten",
]
