"""Turn lark's syntax errors into located InputErrors worded for people.

Lark reports terminal names (`RBRACE`, `__ANON_3`); a user wants to read "expected
'}' or a name". No lark exception leaves btplan.lang: this module is where they stop.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import btplan.lang.lark_version  # noqa: F401  (lark 1.x, checked before it is used)
from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken
from lark.lexer import PatternStr

from btplan.errors import InputError
from btplan.lang.syntax import Source

END = "$END"

MAX_LISTED = 8
"""Beyond this many alternatives the list stops helping; the first ones are shown."""


def expected_words(parser: Lark, names: Iterable[str], words: Mapping[str, str]) -> list[str]:
    """Each expected terminal in words, deduplicated: quoted symbols, keywords, then kinds."""
    found: set[str] = set()
    for name in names:
        if name == END:
            found.add("the end of the file")
        elif name in words:
            found.add(words[name])
        else:
            try:
                pattern = parser.get_terminal(name).pattern
            except KeyError:
                continue
            found.add(f"'{pattern.value}'" if isinstance(pattern, PatternStr) else name.lower())
    return sorted(found, key=lambda s: (not s.startswith("'"), s[1:2].isalpha(), s))


def join_words(found: list[str]) -> str:
    """`'{', 'types' or a name`, cut short when the list stops helping."""
    if len(found) > MAX_LISTED:
        found = [*found[:MAX_LISTED], "..."]
    if not found:
        return "something else"
    if len(found) == 1:
        return found[0]
    return ", ".join(found[:-1]) + " or " + found[-1]


def describe_token(token: Token) -> str:
    """A token quoted for a message, cut to 27 characters and "..." past 30, so that a long
    name or string does not flood the line."""
    text = str(token)
    return f"'{text[:27]}...'" if len(text) > 30 else f"'{text}'"


def _hint(token: Token, expected: list[str]) -> str | None:
    """A likely fix: a misspelt keyword, or a missing comma before a name."""
    text = str(token)
    if not text[:1].isalpha():
        return None
    keywords = [e.strip("'") for e in expected if e.startswith("'") and e[1:2].isalpha()]
    from difflib import get_close_matches  # only a mistake needs it: not imported at start

    near = get_close_matches(text, sorted(keywords), n=1)
    if near:
        return f"did you mean '{near[0]}'?"
    missing = [mark for mark in ("','", "')'") if mark in expected]
    if missing:
        return f"is a {' or '.join(missing)} missing before it?"
    return None


def syntax_error(
    error: UnexpectedInput, parser: Lark, source: Source, words: Mapping[str, str]
) -> InputError:
    """Translate a lark parse error into an InputError at the offending place."""
    if isinstance(error, UnexpectedToken):
        token = error.token
        if token.type == END or token.line is None or token.line < 1:
            where = source.end()
        else:
            where = source.at(token.line, token.column or 1)
        expected = expected_words(parser, error.accepts or error.expected, words)
        if token.type == END:
            return where.error(f"the file ends too early; expected {join_words(expected)}")
        return where.error(
            f"unexpected {describe_token(token)}; expected {join_words(expected)}",
            _hint(token, expected),
        )
    if isinstance(error, UnexpectedCharacters):
        char = error.char
        shown = repr(char) if not char.isprintable() or char.isspace() else f"'{char}'"
        where = source.at(error.line, error.column)
        allowed = join_words(expected_words(parser, error.allowed or (), words))
        return where.error(f"unexpected character {shown}; expected {allowed}")
    if isinstance(error, UnexpectedEOF):
        listed = join_words(expected_words(parser, error.expected, words))
        return source.end().error(f"the file ends too early; expected {listed}")
    return source.start().error(f"cannot read this input: {error}")
