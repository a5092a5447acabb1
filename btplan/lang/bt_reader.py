"""Read the .bt language into located syntax (grammar: grammar/btplan.lark).

The parser is LALR, built once and cached: it runs in linear time and its errors know
exactly which tokens would have been accepted, which makes precise messages possible.
"""

from __future__ import annotations

from functools import cache
from typing import Any

import btplan.lang.lark_version  # noqa: F401  (lark 1.x, checked before it is used)
from lark import Lark, Token, Transformer_NonRecursive
from lark.exceptions import UnexpectedInput, VisitError

from btplan.errors import InputError
from btplan.lang.diagnostics import syntax_error
from btplan.lang.syntax import (
    ActionSyntax,
    DomainSyntax,
    LiteralSyntax,
    Name,
    Number,
    ParameterSyntax,
    PredicateSyntax,
    ProblemSyntax,
    Source,
    TypedSyntax,
)
from btplan.limits import BT_BRACKETS, check_nesting, check_size
from btplan.model import EQUALITY

GRAMMAR_PACKAGE = "btplan.grammar"

WORDS = {"NAME": "a name", "NUMBER": "a number", "REFINED": "'refined'"}
"""How terminals that are not plain strings read in an error message."""

Units = list[DomainSyntax | ProblemSyntax]


@cache
def bt_parser() -> Lark:
    """The .bt parser, loaded from the installed package data (importlib.resources)."""
    return Lark.open_from_package(
        GRAMMAR_PACKAGE, "btplan.lark", parser="lalr", maybe_placeholders=True
    )


def read_bt(text: str, path: str) -> Units:
    """Parse .bt text into domain and problem syntax, in file order.

    Size and nesting are checked first (btplan/limits.py), so that no input, however
    hostile, reaches the parser's or a tree walk's limits.
    """
    check_size(len(text), path)
    check_nesting(text, path, BT_BRACKETS)
    source = Source(text, path)
    parser = bt_parser()
    try:
        tree = parser.parse(text)
    except UnexpectedInput as error:
        raise syntax_error(error, parser, source, WORDS) from None
    try:
        units: Units = _ToSyntax(source).transform(tree)
    except VisitError as error:
        if isinstance(error.orig_exc, InputError):
            raise error.orig_exc from None
        raise
    return units


class _ToSyntax(Transformer_NonRecursive):  # type: ignore[type-arg]
    """One method per grammar rule, named after it, as lark's Transformer expects."""

    def __init__(self, source: Source) -> None:
        super().__init__()
        self.source = source

    def _name(self, token: Token) -> Name:
        return Name(str(token), self.source.at(token.line or 1, token.column or 1))

    def _opt(self, token: Token | None) -> Name | None:
        return None if token is None else self._name(token)

    # --- shared pieces -----------------------------------------------------------------

    def start(self, units: list[Any]) -> Units:
        return list(units)

    def name_list(self, tokens: list[Token]) -> list[Name]:
        return [self._name(t) for t in tokens]

    def typed_line(self, items: list[Any]) -> list[TypedSyntax]:
        names, type_token = items
        type_name = self._opt(type_token)
        return [TypedSyntax(n, type_name) for n in names]

    def parameter(self, items: list[Any]) -> ParameterSyntax:
        name, type_token, refined = items
        return ParameterSyntax(self._name(name), self._name(type_token), refined is not None)

    def atom(self, items: list[Any]) -> LiteralSyntax:
        head, *args = items
        name = self._name(head)
        arg_names = tuple(self._name(a) for a in args if a is not None)
        return LiteralSyntax(name, arg_names, True, name.at)

    def negation(self, items: list[Any]) -> LiteralSyntax:
        (atom,) = items
        return LiteralSyntax(atom.predicate, atom.args, False, atom.at)

    def _equality(self, items: list[Token], positive: bool) -> LiteralSyntax:
        left, right = (self._name(t) for t in items)
        return LiteralSyntax(Name(EQUALITY, left.at), (left, right), positive, left.at)

    def equal(self, items: list[Token]) -> LiteralSyntax:
        return self._equality(items, True)

    def not_equal(self, items: list[Token]) -> LiteralSyntax:
        return self._equality(items, False)

    def literal_list(self, items: list[LiteralSyntax]) -> tuple[LiteralSyntax, ...]:
        return tuple(items)

    # --- domain ------------------------------------------------------------------------

    def types(self, lines: list[list[TypedSyntax]]) -> tuple[str, tuple[TypedSyntax, ...]]:
        return "types", tuple(t for line in lines for t in line)

    def constants(self, lines: list[list[TypedSyntax]]) -> tuple[str, tuple[TypedSyntax, ...]]:
        return "constants", tuple(t for line in lines for t in line)

    def predicate_decl(self, items: list[Any]) -> PredicateSyntax:
        head, *params = items
        return PredicateSyntax(self._name(head), tuple(p for p in params if p is not None))

    def predicates(self, items: list[PredicateSyntax]) -> tuple[str, tuple[PredicateSyntax, ...]]:
        return "predicates", tuple(items)

    def where(self, items: list[Any]) -> tuple[str, Any]:
        return "where", items[0]

    def pre(self, items: list[Any]) -> tuple[str, Any]:
        return "pre", items[0]

    def post(self, items: list[Any]) -> tuple[str, Any]:
        return "post", items[0]

    def cost(self, items: list[Token]) -> tuple[str, Any]:
        return "cost", Number(str(items[0]), self._name(items[0]).at)

    def duration(self, items: list[Token]) -> tuple[str, Any]:
        return "duration", Number(str(items[0]), self._name(items[0]).at)

    def action(self, items: list[Any]) -> tuple[str, ActionSyntax]:
        head, *rest = items
        params = tuple(p for p in rest if isinstance(p, ParameterSyntax))
        fields: dict[str, Any] = {}
        for part in rest:
            if isinstance(part, tuple):
                key, value = part
                if key in fields:
                    raise _first_at(value).error(f"'{key}:' appears twice in this action")
                fields[key] = value
        return "action", ActionSyntax(self._name(head), params, **fields)

    def domain(self, items: list[Any]) -> DomainSyntax:
        head, *parts = items
        lists: dict[str, list[Any]] = {"types": [], "constants": [], "predicates": []}
        actions: list[ActionSyntax] = []
        for key, value in parts:
            if key == "action":
                actions.append(value)
            else:
                lists[key].extend(value)
        return DomainSyntax(
            self._name(head),
            types=tuple(lists["types"]),
            constants=tuple(lists["constants"]),
            predicates=tuple(lists["predicates"]),
            actions=tuple(actions),
        )

    # --- problem -----------------------------------------------------------------------

    def objects(self, lines: list[list[TypedSyntax]]) -> tuple[str, tuple[Any, ...]]:
        return "objects", tuple(t for line in lines for t in line)

    def init(self, items: list[Any]) -> tuple[str, tuple[Any, ...]]:
        return "init", tuple(i for i in items if isinstance(i, LiteralSyntax))

    def goal(self, items: list[Any]) -> tuple[str, tuple[Any, ...]]:
        return "goal", tuple(i for i in items if isinstance(i, LiteralSyntax))

    def problem(self, items: list[Any]) -> ProblemSyntax:
        head, domain, *parts = items
        lists: dict[str, list[Any]] = {"objects": [], "init": [], "goal": []}
        for key, value in parts:
            lists[key].extend(value)
        return ProblemSyntax(
            self._name(head),
            self._name(domain),
            objects=tuple(lists["objects"]),
            init=tuple(lists["init"]),
            goal=tuple(lists["goal"]),
        )


def _first_at(value: Any) -> Any:
    """The place of a duplicated action field: its number, or its first literal."""
    if isinstance(value, Number):
        return value.at
    return value[0].at
