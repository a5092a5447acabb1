"""Read PDDL text as located s-expressions (grammar: grammar/pddl.lark).

Only lists and tokens are found here; btplan/lang/pddl_reader.py gives them meaning.
Reading is iterative, and nesting is bounded before it starts (btplan/limits.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from lark import Lark, Token, Transformer_NonRecursive
from lark.exceptions import UnexpectedInput

from btplan.lang.diagnostics import syntax_error
from btplan.lang.syntax import Source, Where
from btplan.limits import MAX_NESTING, PDDL_BRACKETS, check_nesting, check_size

WORDS = {
    "NAME": "a name",
    "VARIABLE": "a variable",
    "KEYWORD": "a keyword",
    "NUMBER": "a number",
    "SYMBOL": "a symbol",
}


@dataclass(frozen=True, slots=True)
class Word:
    """A token of the s-expression: a name, a variable, a keyword or a symbol."""

    text: str
    kind: str
    at: Where


@dataclass(frozen=True, slots=True)
class Group:
    """A parenthesised list; `at` is its opening parenthesis."""

    items: tuple[Item, ...]
    at: Where

    def head(self) -> str | None:
        first = self.items[0] if self.items else None
        return first.text if isinstance(first, Word) else None


Item = Word | Group


@cache
def pddl_parser() -> Lark:
    """The PDDL s-expression parser, loaded from the installed package data."""
    return Lark.open_from_package("btplan.grammar", "pddl.lark", parser="lalr")


def read_items(text: str, path: str) -> list[Item]:
    """The top-level items of a PDDL text, or a located syntax error.

    Size and nesting are checked first (btplan/limits.py): a 10,000-deep `(and (and ...`
    is refused at the first parenthesis too deep, not read.
    """
    check_size(len(text), path)
    check_nesting(text, path, PDDL_BRACKETS,
                  message=f"parentheses nested more than {MAX_NESTING} levels deep")
    source = Source(text, path)
    parser = pddl_parser()
    try:
        tree = parser.parse(text)
    except UnexpectedInput as error:
        raise syntax_error(error, parser, source, WORDS) from None
    items: list[Item] = _ToItems(source).transform(tree)
    return items


class _ToItems(Transformer_NonRecursive):  # type: ignore[type-arg]
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
        assert isinstance(opening, Token)
        where = self.source.at(opening.line or 1, opening.column or 1)
        return Group(self._items(children[1:-1]), where)


# --- expectations, as the PDDL reader states them ---------------------------------------


def place(item: Item | None, parent: Group) -> Where:
    return item.at if item is not None else parent.at


def expect_group(item: Item | None, what: str, parent: Group | None = None) -> Group:
    if isinstance(item, Group):
        return item
    where = item.at if item is not None else (parent.at if parent else None)
    assert where is not None
    raise where.error(f"expected {what}")


def expect_word(item: Item | None, parent: Group, text: str | None, what: str) -> Word:
    if isinstance(item, Word) and item.kind == "NAME" and (text is None or item.text == text):
        return item
    raise place(item, parent).error(f"expected {what}")
