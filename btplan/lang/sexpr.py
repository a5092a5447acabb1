"""Read PDDL text as located s-expressions (grammar: grammar/pddl.lark).

Only lists and tokens are found here; btplan/lang/pddl_reader.py gives them meaning.
Reading is iterative, and nesting is bounded before it starts (btplan/limits.py).

Well-formed text is read by one regular expression with the grammar's tokens, which
takes a few milliseconds; building the lark parser from the grammar took longer than
planning a small problem (start-up counts for a command-line planner). Text that the
fast reader refuses goes to the lark parser, so that every syntax error is worded
and located as before (btplan/lang/diagnostics.py).
"""

from __future__ import annotations

import re
from functools import cache

from btplan.lang.syntax import Source, Where
from btplan.limits import MAX_NESTING, PDDL_BRACKETS, check_nesting, check_size

TYPE_CHECKING = False
if TYPE_CHECKING:
    import btplan.lang.lark_version  # noqa: F401
    from lark import Lark, Token, Transformer_NonRecursive

WORDS = {
    "NAME": "a name",
    "VARIABLE": "a variable",
    "KEYWORD": "a keyword",
    "NUMBER": "a number",
    "SYMBOL": "a symbol",
}

if TYPE_CHECKING:
    from typing import NamedTuple

    class Word(NamedTuple):
        """A token of the s-expression: a name, a variable, a keyword or a symbol."""

        text: str
        kind: str
        at: Where

    class Group(NamedTuple):
        """A parenthesised list; `at` is its opening parenthesis."""

        items: tuple[Item, ...]
        at: Where

        def head(self) -> str | None: ...

else:  # the same named tuples, written out (as btplan/atoms.py writes Atom): a file's
    # every token and list is one of them, and a tuple is made in C where a record's
    # fields are set one by one (about 1 us each, of a small problem's 4-5 ms reading)
    from collections import _tuplegetter

    class Word(tuple):
        """A token of the s-expression: a name, a variable, a keyword or a symbol."""

        __slots__ = ()
        __match_args__ = ("text", "kind", "at")
        text = _tuplegetter(0, "The token's text (lower case but for symbols).")
        kind = _tuplegetter(1, "Its terminal: NAME, VARIABLE, KEYWORD, NUMBER or SYMBOL.")
        at = _tuplegetter(2, "Where it starts.")

        def __new__(cls, text, kind, at):
            return _new_tuple(cls, (text, kind, at))

        def __repr__(self):
            return f"Word(text={self[0]!r}, kind={self[1]!r}, at={self[2]!r})"

    class Group(tuple):
        """A parenthesised list; `at` is its opening parenthesis."""

        __slots__ = ()
        __match_args__ = ("items", "at")
        items = _tuplegetter(0, "What the parentheses hold, in order.")
        at = _tuplegetter(1, "Where the opening parenthesis is.")

        def __new__(cls, items, at):
            return _new_tuple(cls, (items, at))

        def __repr__(self):
            return f"Group(items={self[0]!r}, at={self[1]!r})"

        def head(self):
            """The first item's text when it is a word (`define`, `:action`), else None."""
            first = self[0][0] if self[0] else None
            return first[0] if isinstance(first, Word) else None


_new_tuple = tuple.__new__

Item = Word | Group


@cache
def pddl_parser() -> Lark:
    """The PDDL s-expression parser, loaded from the installed package data."""
    import btplan.lang.lark_version  # noqa: F401
    from lark import Lark

    return Lark.open_from_package("btplan.grammar", "pddl.lark", parser="lalr")


SKIP = r"(?:[ \t\f\r\n]++|;[^\n]*+)*+"
"""Whitespace and comments, as many as follow (possessive: never given back, so that
no token is found inside a comment)."""

TOKEN = re.compile(SKIP + r"""(?:
    (?P<LPAR>\()
  | (?P<RPAR>\))
  | (?P<NAME>[A-Za-z][A-Za-z0-9_\-]*)
  | (?P<VARIABLE>\?[A-Za-z][A-Za-z0-9_\-]*)
  | (?P<KEYWORD>:[A-Za-z][A-Za-z0-9_\-]*)
  | (?P<NUMBER>[0-9]+(?:\.[0-9]+)?)
  | (?P<SYMBOL>[-=<>*/+]+)
)""", re.VERBOSE)
"""One terminal of grammar/pddl.lark with the whitespace and comments before it: one
match a token, where matching the skipped text on its own took as many again. The
terminals' first characters differ, so the first alternative that matches is lark's
longest match."""

SKIPPED = re.compile(SKIP)
"""What may follow the last token."""


def read_items(text: str, path: str) -> list[Item]:
    """The top-level items of a PDDL text, or a located syntax error.

    Size and nesting are checked first (btplan/limits.py): a 10,000-deep `(and (and ...`
    is refused at the first parenthesis too deep, not read.
    """
    check_size(len(text), path)
    check_nesting(text, path, PDDL_BRACKETS,
                  message=f"parentheses nested more than {MAX_NESTING} levels deep")
    source = Source(text, path)
    items = _read_fast(text, source)
    return items if items is not None else _read_with_lark(text, source)


def _read_fast(text: str, source: Source) -> list[Item] | None:
    """The items of well-formed text; None for anything else (lark then says what)."""
    stack: list[tuple[list[Item], Where | None]] = [([], None)]
    line, line_start = 1, 0
    position = 0
    match = TOKEN.match
    while (found := match(text, position)) is not None:
        kind = found.lastgroup
        start = found.start(kind)  # type: ignore[arg-type]  # a token matched: it has one
        if start != position:
            breaks = text.count("\n", position, start)
            if breaks:
                line += breaks
                line_start = text.rindex("\n", position, start) + 1
        position = found.end()
        column = start - line_start + 1
        if kind == "LPAR":
            stack.append(([], source.at(line, column)))
        elif kind == "RPAR":
            if len(stack) == 1:
                return None
            children, opened = stack.pop()
            assert opened is not None
            stack[-1][0].append(_new_tuple(Group, (tuple(children), opened)))
        else:
            word = text[start:position]
            stack[-1][0].append(_new_tuple(Word, (word if kind == "SYMBOL" else word.lower(),
                                                  kind, source.at(line, column))))
    if SKIPPED.fullmatch(text, position) is None:
        return None  # a character no token starts with
    return stack[0][0] if len(stack) == 1 else None


def _read_with_lark(text: str, source: Source) -> list[Item]:
    """Parse with the grammar: a located, worded syntax error for text the fast reader
    refused (and the items, should the two ever disagree)."""
    from lark.exceptions import UnexpectedInput

    from btplan.lang.diagnostics import syntax_error

    parser = pddl_parser()
    try:
        tree = parser.parse(text)
    except UnexpectedInput as error:
        raise syntax_error(error, parser, source, WORDS) from None
    items: list[Item] = _to_items(source).transform(tree)
    return items


def _to_items(source: Source) -> Transformer_NonRecursive:  # type: ignore[type-arg]
    from lark import Transformer_NonRecursive

    class ToItems(_ToItems, Transformer_NonRecursive):  # type: ignore[type-arg]
        pass

    return ToItems(source)


class _ToItems:
    """Lark's tree to items (mixed into lark's transformer when lark is imported)."""

    def __init__(self, source: Source) -> None:
        super().__init__()
        self.source = source

    def word(self, token: Token) -> Word:
        where = self.source.at(token.line or 1, token.column or 1)
        text = str(token).lower() if token.type != "SYMBOL" else str(token)
        return Word(text, token.type, where)

    def _items(self, children: list[Token | Group]) -> tuple[Item, ...]:
        return tuple(c if isinstance(c, Group) else self.word(c) for c in children)

    def start(self, children: list[Token | Group]) -> list[Item]:
        return list(self._items(children))

    def list(self, children: list[Token | Group]) -> Group:
        opening = children[0]
        assert not isinstance(opening, Group)
        where = self.source.at(opening.line or 1, opening.column or 1)
        return Group(self._items(children[1:-1]), where)


# --- expectations, as the PDDL reader states them ---------------------------------------


def place(item: Item | None, parent: Group) -> Where:
    """Where `item` stands, or its parent group's place when the item is missing (a list that
    ended early), so that an error still points into the input."""
    return item.at if item is not None else parent.at


def expect_group(item: Item | None, what: str, parent: Group | None = None) -> Group:
    """`item` if it is a group; else an InputError "expected {what}" at it, or at `parent` when
    it is missing (a caller whose item may be missing must give `parent`)."""
    if isinstance(item, Group):
        return item
    where = item.at if item is not None else (parent.at if parent else None)
    assert where is not None
    raise where.error(f"expected {what}")


def expect_word(item: Item | None, parent: Group, text: str | None, what: str) -> Word:
    """`item` if it is a NAME word (and exactly `text`, if given); else an InputError
    "expected {what}" at it, or at `parent` when it is missing."""
    if isinstance(item, Word) and item.kind == "NAME" and (text is None or item.text == text):
        return item
    raise place(item, parent).error(f"expected {what}")
