"""Turn lark's syntax errors into located InputErrors worded for people.

Lark reports terminal names (`RBRACE`, `__ANON_3`); a user wants to read "expected
'}' or a name". No lark exception leaves btplan.lang: this module is where they stop.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from lark import Lark, Token
from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken
from lark.lexer import PatternStr

from btplan.errors import InputError
from btplan.lang.syntax import Source

END = "$END"

MAX_LISTED = 8
"""Beyond this many alternatives the list stops helping; the first ones are shown."""


def describe_terminals(parser: Lark, names: Iterable[str], words: Mapping[str, str]) -> str:
    """`'{', 'types' or a name`: each expected terminal in words, sorted, deduplicated."""
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
            if isinstance(pattern, PatternStr):
                found.add(f"'{pattern.value}'")
            else:
                found.add(name.lower())
    # quoted symbols first, then keywords, then descriptions, each alphabetically
    ordered = sorted(
        found, key=lambda s: (not s.startswith("'"), s.startswith("'") and s[1:2].isalpha(), s)
    )
    if len(ordered) > MAX_LISTED:
        ordered = ordered[:MAX_LISTED] + ["..."]
    if not ordered:
        return "something else"
    if len(ordered) == 1:
        return ordered[0]
    return ", ".join(ordered[:-1]) + " or " + ordered[-1]


def describe_token(token: Token, words: Mapping[str, str]) -> str:
    if token.type == END:
        return "the end of the file"
    text = str(token)
    if len(text) > 30:
        text = text[:27] + "..."
    kind = words.get(token.type)
    return f"'{text}'" if kind is None or not kind.startswith("a") else f"{kind} '{text}'"


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
        found = describe_token(token, words)
        return where.error(
            f"unexpected {found}; expected {describe_terminals(parser, error.accepts or error.expected, words)}"
        )
    if isinstance(error, UnexpectedCharacters):
        char = error.char
        shown = repr(char) if not char.isprintable() or char.isspace() else f"'{char}'"
        where = source.at(error.line, error.column)
        allowed = describe_terminals(parser, error.allowed or (), words)
        return where.error(f"unexpected character {shown}; expected {allowed}")
    if isinstance(error, UnexpectedEOF):
        expected = describe_terminals(parser, error.expected, words)
        return source.end().error(f"the file ends too early; expected {expected}")
    return source.start().error(f"cannot read this input: {error}")
