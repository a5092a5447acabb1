"""Typed lists of PDDL (`a b - t`), with the forms competitions use.

`(either t u)` in a predicate's parameters reads as the nearest common ancestor of t
and u: a predicate's types only check facts, so nothing is lost. A type declared under
`object` and again under another type keeps the other (IPC's storage domain does this).
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.lang.sexpr import Group, Item, Word
from btplan.lang.syntax import Name, TypedSyntax
from btplan.model import ROOT_TYPE


def name_of(word: Word) -> Name:
    """A parsed word as a located Name, so validation can still point at it."""
    return Name(word.text, word.at)


def typed_list(
    items: tuple[Item, ...], kind: str, parents: Mapping[str, str | None] | None = None
) -> list[tuple[Word, Word | None]]:
    """`a b - t c` -> [(a, t), (b, t), (c, None)]; `kind` is NAME or VARIABLE.

    With `parents` (the types declared so far), `(either t u)` reads as the nearest
    common ancestor of t and u; without, it is refused.
    """
    out: list[tuple[Word, Word | None]] = []
    pending: list[Word] = []
    index = 0
    while index < len(items):
        item = items[index]
        if isinstance(item, Word) and item.text == "-":
            type_item = items[index + 1] if index + 1 < len(items) else None
            if isinstance(type_item, Group) and type_item.head() == "either":
                if parents is None:
                    raise type_item.at.error(
                        "'either' types are not supported here", "only in a predicate's parameters")
                type_item = _common_ancestor(type_item, parents)
            if not isinstance(type_item, Word) or type_item.kind != "NAME":
                raise (type_item or item).at.error("expected a type name after '-'")
            if not pending:
                raise item.at.error("a type after '-' must follow the names it types")
            out.extend((w, type_item) for w in pending)
            pending = []
            index += 2
            continue
        if not isinstance(item, Word) or item.kind != kind:
            expected = "a variable such as ?x" if kind == "VARIABLE" else "a name"
            raise item.at.error(f"expected {expected}")
        pending.append(item)
        index += 1
    out.extend((w, None) for w in pending)
    return out


def _common_ancestor(either: Group, parents: Mapping[str, str | None]) -> Word:
    """The nearest type every member of `(either t u ...)` derives from, located there."""
    members = [m for m in either.items[1:] if isinstance(m, Word) and m.kind == "NAME"]
    if not members or len(members) != len(either.items) - 1:
        raise either.at.error("expected type names after 'either'")

    def chain(name: str) -> list[str]:
        out = [name]
        while (parent := parents.get(out[-1])) is not None and parent not in out:
            out.append(parent)
        return out if out[-1] == ROOT_TYPE else [*out, ROOT_TYPE]

    shared = chain(members[0].text)
    for member in members[1:]:
        theirs = set(chain(member.text))
        shared = [t for t in shared if t in theirs]
    return Word(shared[0] if shared else ROOT_TYPE, "NAME", either.at)


def typed(items: tuple[Item, ...]) -> tuple[TypedSyntax, ...]:
    """A `:types`, `:constants` or `:objects` list as located entries; `(either ...)` is
    refused here, as only a predicate's parameters accept it."""
    return tuple(
        TypedSyntax(name_of(w), name_of(t) if t else None) for w, t in typed_list(items, "NAME")
    )


def merged(types: list[TypedSyntax]) -> list[TypedSyntax]:
    """A type declared twice, once under `object` and once under another type, is kept
    under the other (IPC's storage domain declares `area - object` and `area - surface`)."""
    parents: dict[str, set[str]] = {}
    for entry in types:
        parent = entry.type.text if entry.type else ROOT_TYPE
        parents.setdefault(entry.name.text, set()).add(parent)
    out: list[TypedSyntax] = []
    for entry in types:
        parent = entry.type.text if entry.type else ROOT_TYPE
        if parent == ROOT_TYPE and len(parents[entry.name.text]) == 2:
            continue  # the other declaration is the more specific one
        out.append(entry)
    return out


def implicit_types(declared: list[TypedSyntax]) -> list[TypedSyntax]:
    """Parents named only after '-' (`truck car - vehicle`): PDDL declares them too."""
    names = {t.name.text for t in declared} | {ROOT_TYPE}
    implicit: dict[str, TypedSyntax] = {}
    for entry in declared:
        if entry.type is not None and entry.type.text not in names:
            implicit.setdefault(entry.type.text, TypedSyntax(entry.type, None))
    return list(implicit.values())
