"""The type hierarchy of a domain while it is checked: resolution, cycles, subtyping.

`object` is the built-in root, and a type declared without a parent derives from it.
A domain may also place `object` itself under a type of its own (the paper's example
says every object is a location the robot can approach: `object : location`); then
the types declared without a parent are top-level types, so that the hierarchy stays
a forest instead of becoming a cycle.
"""

from __future__ import annotations

from collections.abc import Iterable

from btplan.lang.names import suggest
from btplan.lang.syntax import Name, TypedSyntax
from btplan.limits import MAX_TYPE_DEPTH
from btplan.model import ROOT_TYPE, Domain, TypeDef


class TypeTable:
    """Declared types and their parents, checked for unknown parents and cycles."""

    def __init__(self, parents: dict[str, str | None]) -> None:
        self.parents = parents

    @classmethod
    def from_domain(cls, domain: Domain) -> TypeTable:
        """The table of a domain that was already validated: no checks are repeated."""
        return cls(dict(domain.type_parents))

    @classmethod
    def from_syntax(cls, entries: Iterable[TypedSyntax]) -> TypeTable:
        """The table of declared types, checked: a type declared twice, an unknown parent, a cycle
        or a chain deeper than MAX_TYPE_DEPTH raises an InputError at the declaration. When
        `object` itself is given a parent, types without one are top-level (module docstring)."""
        entries = list(entries)
        seen: dict[str, Name] = {}
        for entry in entries:
            if entry.name.text in seen and entry.name.text != ROOT_TYPE:
                raise entry.name.at.error(
                    f"type '{entry.name.text}' is declared twice",
                    f"first declared at {seen[entry.name.text].at.span}",
                )
            seen[entry.name.text] = entry.name
        root_demoted = any(e.name.text == ROOT_TYPE and e.type is not None for e in entries)
        default_parent = None if root_demoted else ROOT_TYPE
        parents: dict[str, str | None] = {} if root_demoted else {ROOT_TYPE: None}
        for entry in entries:
            if entry.name.text == ROOT_TYPE and entry.type is None:
                continue
            parents[entry.name.text] = entry.type.text if entry.type else default_parent
        table = cls(parents)
        for entry in entries:
            if entry.type is not None:
                table.resolve(entry.type)
        table._check_cycles(entries)
        return table

    def _check_cycles(self, entries: list[TypedSyntax]) -> None:
        """Refuse cycles, and chains deeper than MAX_TYPE_DEPTH, in linear time.

        Each type's depth is remembered once known, so a long chain is walked once,
        not once per type on it (which took hours for 10,000 types).
        """
        depth: dict[str, int] = {}
        for entry in entries:
            chain: list[str] = []
            on_chain: set[str] = set()
            current: str | None = entry.name.text
            while current is not None and current not in depth:
                if current in on_chain:
                    loop = " -> ".join([*chain[chain.index(current) :], current])
                    raise entry.name.at.error(f"the type hierarchy has a cycle: {loop}")
                chain.append(current)
                on_chain.add(current)
                current = self.parents.get(current)
            below = depth[current] if current is not None else 0
            for offset, name in enumerate(reversed(chain), start=1):
                depth[name] = below + offset
            if depth[entry.name.text] > MAX_TYPE_DEPTH:
                raise entry.name.at.error(
                    f"the type hierarchy is more than {MAX_TYPE_DEPTH} levels deep here",
                    "btplan reads no deeper; see 'Hostile input' in docs/reliability.md",
                )

    def resolve(self, name: Name | None) -> str:
        """The name of a declared type; an omitted type means the root."""
        if name is None:
            return ROOT_TYPE
        if name.text not in self.parents and name.text != ROOT_TYPE:
            raise name.at.error(f"unknown type '{name.text}'", suggest(name.text, self.parents))
        return name.text

    def ancestors(self, name: str) -> list[str]:
        """`name` and its parents up to the top, nearest first; the walk stops at a repeat, so a
        cycle not yet refused cannot hang it."""
        chain: list[str] = []
        current: str | None = name
        while current is not None and current not in chain:
            chain.append(current)
            current = self.parents.get(current)
        return chain

    def is_subtype(self, name: str, of: str) -> bool:
        """Whether `name` is `of` or derives from it; every type derives from `object` when the
        table has no entry for it (a hierarchy that leaves the root implicit)."""
        return of in self.ancestors(name) or (of == ROOT_TYPE and ROOT_TYPE not in self.parents)

    def related(self, a: str, b: str) -> bool:
        """True when some object could be of both types: one is a subtype of the other."""
        return self.is_subtype(a, b) or self.is_subtype(b, a)

    def definitions(self) -> tuple[TypeDef, ...]:
        """The table as the model's TypeDefs, `object` among them, for the Domain that
        validation builds."""
        return tuple(TypeDef(name=n, parent=p) for n, p in self.parents.items())
