"""Atom and GroundLiteral behave as the named tuples they are declared as.

btplan/model.py writes them out as tuple subclasses (making a named tuple compiles
source, and a plan run compiles nothing else); here they are compared with real named
tuples of the same fields, which `typing.NamedTuple` makes.
"""

from __future__ import annotations

import copy
import pickle
from typing import Any, NamedTuple

import pytest

from btplan.model import Atom, GroundLiteral, atoms


class AtomTuple(NamedTuple):
    predicate: str
    args: tuple[str, ...]


class LiteralTuple(NamedTuple):
    atom: AtomTuple
    positive: bool = True


def test_fields_construction_and_defaults_match_named_tuples() -> None:
    for ours, theirs in ((Atom, AtomTuple), (GroundLiteral, LiteralTuple)):
        assert ours._fields == theirs._fields
        assert ours._field_defaults == theirs._field_defaults
        assert ours.__match_args__ == theirs.__match_args__
    atom = Atom(predicate="on", args=("a", "b"))
    assert (atom.predicate, atom.args) == ("on", ("a", "b"))
    assert GroundLiteral(atom).positive is True
    assert GroundLiteral(atom=atom, positive=False).positive is False
    make: Any = Atom
    bare: Any = GroundLiteral
    for kind, args, kwargs in ((make, ("on",), {}), (make, ("on", (), ()), {}), (bare, (), {}),
                               (make, ("on",), {"args": (), "predicate": "x"})):
        with pytest.raises(TypeError):
            kind(*args, **kwargs)


def test_equality_hashing_order_and_repr_are_the_named_tuples() -> None:
    ours: Any = GroundLiteral(Atom("on", ("a", "b")), False)
    theirs = LiteralTuple(AtomTuple("on", ("a", "b")), False)
    assert ours == theirs == (("on", ("a", "b")), False)
    assert hash(ours) == hash(theirs) == hash((("on", ("a", "b")), False))
    assert Atom("a", ()) < Atom("b", ()) and Atom("a", ("x",)) > Atom("a", ())
    assert repr(ours) == repr(theirs).replace("LiteralTuple", "GroundLiteral").replace(
        "AtomTuple", "Atom")
    assert str(ours) == "not on(a, b)" and str(ours.atom) == "on(a, b)"
    assert ours.atom in {("on", ("a", "b"))} and ("on", ("a", "b")) in atoms([("on", ("a", "b"))])
    assert not hasattr(ours, "__dict__")
    with pytest.raises(AttributeError):
        ours.positive = True


def test_copies_pickles_and_matches_keep_the_class() -> None:
    literal = GroundLiteral(Atom("on", ("a", "b")), False)
    for again in (copy.copy(literal), copy.deepcopy(literal),
                  pickle.loads(pickle.dumps(literal)), pickle.loads(pickle.dumps(literal, 0))):
        assert again == literal and type(again) is GroundLiteral and type(again.atom) is Atom
    match literal:
        case GroundLiteral(Atom(predicate, args), positive):
            assert (predicate, args, positive) == ("on", ("a", "b"), False)
        case _:
            pytest.fail("no match")


def test_holds_reads_the_state_with_the_wildcard() -> None:
    state = atoms([("on", ("a", "b")), ("clear", ("a",))])
    assert GroundLiteral(Atom("on", ("a", "b"))).holds(state)
    assert not GroundLiteral(Atom("on", ("a", "b")), False).holds(state)
    assert not GroundLiteral(Atom("on", ("_", "b")), False).holds(state)
    assert GroundLiteral(Atom("on", ("_", "c")), False).holds(state)
