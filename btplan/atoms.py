"""Grounded atoms and literals: the facts every layer hashes and compares.

They are plain named tuples, so the planner and the worlds hash and compare millions of
them at C speed, written out by hand because making a named tuple compiles source
(tests/test_model_tuples.py checks them against real named tuples). This module imports
nothing from btplan; btplan.model re-exports what it defines.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, NamedTuple
else:
    from collections import _tuplegetter  # the field access of named tuples, in C

    _new_tuple = tuple.__new__

WILDCARD = "_"
"""In a negative postcondition, `_` matches any object: `not near(_)` clears them all."""


def _atom_text(atom: Atom) -> str:
    return f"{atom.predicate}({', '.join(atom.args)})"


def _holds(literal: GroundLiteral, state: frozenset[Atom] | set[Atom]) -> bool:
    if literal.positive:
        return literal.atom in state
    if literal.atom in state:
        return False
    # `not blocks(_, t)`: no atom of the state matches the pattern.
    return WILDCARD not in literal.atom.args or not any(matches(literal.atom, a) for a in state)


def _literal_text(literal: GroundLiteral) -> str:
    return str(literal.atom) if literal.positive else f"not {literal.atom}"


if TYPE_CHECKING:  # what type checkers see: two named tuples

    class Atom(NamedTuple):
        """A ground fact, e.g. Atom("holding", ("cube",)).

        Equal to, and hashed like, the plain tuple ("holding", ("cube",)): behavior-tree
        leaves use that tuple as their key, so a world can look leaves up in a set of atoms.
        """

        predicate: str
        args: tuple[str, ...]

        def __str__(self) -> str:
            return _atom_text(self)

    class GroundLiteral(NamedTuple):
        atom: Atom
        positive: bool = True

        def holds(self, state: frozenset[Atom] | set[Atom]) -> bool:
            return _holds(self, state)

        def __str__(self) -> str:
            return _literal_text(self)

else:  # the same named tuples, written out: `typing.NamedTuple` and
    # `collections.namedtuple` compile source when the class is made, and the first
    # compile of a process costs 4-8 ms, a tenth of a whole small `btplan plan`
    # (tests/test_model_tuples.py checks these against real named tuples).

    class Atom(tuple):
        """A ground fact, e.g. Atom("holding", ("cube",)).

        Equal to, and hashed like, the plain tuple ("holding", ("cube",)): behavior-tree
        leaves use that tuple as their key, so a world can look leaves up in a set of atoms.
        """

        __slots__ = ()
        _fields = ("predicate", "args")
        _field_defaults: dict[str, Any] = {}
        __match_args__ = _fields
        predicate = _tuplegetter(0, "Alias for field number 0")
        args = _tuplegetter(1, "Alias for field number 1")

        def __new__(cls, predicate, args):
            return _new_tuple(cls, (predicate, args))

        def __repr__(self):
            return f"{type(self).__name__}(predicate={self[0]!r}, args={self[1]!r})"

        def __getnewargs__(self):
            return tuple(self)

        __str__ = _atom_text

    class GroundLiteral(tuple):
        __slots__ = ()
        _fields = ("atom", "positive")
        _field_defaults: dict[str, Any] = {"positive": True}
        __match_args__ = _fields
        atom = _tuplegetter(0, "Alias for field number 0")
        positive = _tuplegetter(1, "Alias for field number 1")

        def __new__(cls, atom, positive=True):
            return _new_tuple(cls, (atom, positive))

        def __repr__(self):
            return f"{type(self).__name__}(atom={self[0]!r}, positive={self[1]!r})"

        def __getnewargs__(self):
            return tuple(self)

        holds = _holds
        __str__ = _literal_text


def matches(pattern: Atom, atom: Atom) -> bool:
    """True when `atom` is an instance of `pattern`, whose `_` arguments match anything."""
    if pattern.predicate != atom.predicate or len(pattern.args) != len(atom.args):
        return False
    return all(p == WILDCARD or p == a for p, a in zip(pattern.args, atom.args))
