"""Parse untrusted XML into a small element tree that remembers lines and columns.

Trees come from other people's projects, so the parser refuses what BT XML never
needs: a DOCTYPE (and with it every entity declaration, the "billion laughs" and
external entities that read local files or the network). It also bounds the size of
the text, the nesting depth and the number of elements, so a hostile or broken file
gives one located error instead of exhausting memory or the Python stack. expat is
used directly because ElementTree keeps no positions.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.parsers import expat

from btplan.bt.formats.locate import line_at
from btplan.errors import InputError, Span

MAX_CHARS = 20_000_000
"""Largest XML text read (a real tree file is a few hundred kilobytes at most)."""
MAX_DEPTH = 200
"""Deepest element nesting read; the readers recurse once per level."""
MAX_ELEMENTS = 500_000
"""Most elements in one file."""


@dataclass
class Element:
    """One XML element: its tag, attributes in file order, place, and child elements."""

    tag: str
    attrs: dict[str, str]
    line: int
    column: int
    path: str = ""
    children: list[Element] = field(default_factory=list)
    text: str = ""


class _Refused(Exception):
    """Raised inside expat callbacks; turned into an InputError at the current position."""

    def __init__(self, message: str, hint: str | None = None) -> None:
        super().__init__(message)
        self.message, self.hint = message, hint


def parse_xml(text: str, path: str) -> Element:
    """The document element of `text`, or an InputError located in `path`."""
    if len(text) > MAX_CHARS:
        raise InputError(f"the XML text is larger than {MAX_CHARS:,} characters",
                         Span(path, 1, 1), "split it into files joined with <include>")
    parser = expat.ParserCreate()
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[Element] = [Element("#document", {}, 1, 1)]
    count = 0

    def start(tag: str, attrs: dict[str, str]) -> None:
        nonlocal count
        count += 1
        if len(stack) > MAX_DEPTH:
            raise _Refused(f"elements are nested more than {MAX_DEPTH} deep")
        if count > MAX_ELEMENTS:
            raise _Refused(f"more than {MAX_ELEMENTS:,} elements")
        element = Element(tag, attrs, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1,
                          path)
        stack[-1].children.append(element)
        stack.append(element)

    def end(tag: str) -> None:
        stack.pop()

    def data(chunk: str) -> None:
        stack[-1].text += chunk

    def doctype(*_: object) -> None:
        raise _Refused("a DOCTYPE is not allowed in a tree file",
                       "remove it; BT XML needs no DTD or entities")

    def external(*_: object) -> int:
        raise _Refused("external entities are not read")

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = data
    parser.StartDoctypeDeclHandler = doctype
    parser.EntityDeclHandler = doctype
    parser.ExternalEntityRefHandler = external
    try:
        parser.Parse(text, True)
    except _Refused as refused:
        line = parser.CurrentLineNumber
        raise InputError(refused.message, Span(path, line, parser.CurrentColumnNumber + 1),
                         refused.hint, line_at(text, line)) from None
    except expat.ExpatError as error:
        line = error.lineno
        raise InputError(f"not well-formed XML: {expat.ErrorString(error.code)}",
                         Span(path, line, error.offset + 1), source_line=line_at(text, line)
                         ) from None
    except (UnicodeError, ValueError, RecursionError) as error:
        raise InputError(f"cannot read this XML text: {type(error).__name__}",
                         Span(path, 1, 1)) from None
    if not stack[0].children:
        raise InputError("no XML element found", Span(path, 1, 1))
    return stack[0].children[0]


__all__ = ["MAX_CHARS", "MAX_DEPTH", "MAX_ELEMENTS", "Element", "parse_xml"]
