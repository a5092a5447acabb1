"""btplan.records makes the classes `dataclasses.dataclass` makes: checked side by side.

Every class below is declared twice, once as a dataclass and once as a record, with the
same options; construction, errors, repr, equality, hashing, immutability, copying and
the dataclasses functions must agree.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from typing import Any

import pytest

from btplan import records
from btplan.model import Domain, Literal, Task, TypeDef


def both(warm: bool = False, **options: Any) -> tuple[type[Any], type[Any]]:
    """The same class body as a dataclass and as a record; `warm`: the record class has
    made enough records to have an `__init__` of its own (records.HOT)."""
    made = []
    for decorate, field in ((dataclasses.dataclass, dataclasses.field),
                            (records.record, records.field)):
        class Point:
            x: int
            y: int = 2
            tags: list[str] = field(default_factory=list)

            def total(self) -> int:
                return self.x + self.y

        made.append(decorate(**options)(Point))
    if warm:
        for _ in range(records.HOT):
            made[1](x=0)
        assert made[1].__init__ is not records._init
    return made[0], made[1]


OPTIONS = [{}, {"frozen": True}, {"frozen": True, "slots": True}, {"kw_only": True},
           {"frozen": True, "kw_only": True}, {"slots": True}]


@pytest.mark.parametrize("warm", [False, True])
@pytest.mark.parametrize("options", OPTIONS)
def test_construction_repr_and_equality_agree(options: dict[str, Any], warm: bool) -> None:
    dc, rec = both(warm, **options)
    for args, kwargs in (((), {"x": 1}), ((), {"x": 1, "y": 5, "tags": ["a"]})):
        a, b = dc(*args, **kwargs), rec(*args, **kwargs)
        assert repr(a) == repr(b)
        assert b == rec(*args, **kwargs) and b != rec(x=99)
        assert (b == a) is False  # another class, as between two dataclasses
        assert b.total() == a.total()
    assert rec(x=1).tags == [] and rec(x=1).tags is not rec(x=1).tags
    if not options.get("kw_only"):
        assert repr(rec(1, 3)) == repr(dc(1, 3))
    assert rec.__match_args__ == dc.__match_args__


@pytest.mark.parametrize("warm", [False, True])
@pytest.mark.parametrize("options", OPTIONS)
def test_bad_arguments_are_refused_alike(options: dict[str, Any], warm: bool) -> None:
    dc, rec = both(warm, **options)
    for args, kwargs in (((), {}), ((), {"x": 1, "z": 2}), ((1, 2, [], 4), {}),
                         ((1,), {"x": 1})):
        with pytest.raises(TypeError):
            dc(*args, **kwargs)
        with pytest.raises(TypeError):
            rec(*args, **kwargs)


@pytest.mark.parametrize("warm", [False, True])
@pytest.mark.parametrize("options", OPTIONS)
def test_hashing_and_immutability_agree(options: dict[str, Any], warm: bool) -> None:
    dc, rec = both(warm, **options)
    a, b = dc(x=1, tags=()), rec(x=1, tags=())
    assert (dc.__hash__ is None) == (rec.__hash__ is None)
    if options.get("frozen"):
        assert hash(b) == hash(rec(x=1, tags=()))
        with pytest.raises(dataclasses.FrozenInstanceError):
            b.x = 2
        with pytest.raises(dataclasses.FrozenInstanceError):
            del b.x
    else:
        b.x = a.x = 7
        assert b.x == 7
    assert hasattr(b, "__dict__") == hasattr(a, "__dict__")


@pytest.mark.parametrize("warm", [False, True])
@pytest.mark.parametrize("options", OPTIONS)
def test_copies_and_dataclass_functions_agree(options: dict[str, Any], warm: bool) -> None:
    dc, rec = both(warm, **options)
    a, b = dc(x=1, tags=["t"]), rec(x=1, tags=["t"])
    assert dataclasses.is_dataclass(b)
    assert [f.name for f in dataclasses.fields(b)] == [f.name for f in dataclasses.fields(a)]
    assert dataclasses.asdict(b) == dataclasses.asdict(a)
    assert dataclasses.replace(b, y=9) == records.replace(b, y=9) == rec(x=1, y=9, tags=["t"])
    assert records.replace(b) is not b
    for copied in (copy.copy(b), copy.deepcopy(b)):
        assert copied == b
    if "<locals>" not in rec.__qualname__:
        assert pickle.loads(pickle.dumps(b)) == b


def test_frozen_slotted_records_pickle_and_copy() -> None:
    from btplan.errors import Span

    span = Span("d.pddl", 3, 4)
    for copied in (pickle.loads(pickle.dumps(span)), copy.deepcopy(span), copy.copy(span)):
        assert copied == span and hash(copied) == hash(span) and copied is not span
    assert not hasattr(span, "__dict__")


@pytest.mark.parametrize("warm", [False, True])
def test_a_subclass_inherits_fields_and_defaults_alike(warm: bool) -> None:
    dc, rec = both(warm)
    made = []
    for decorate, base in ((dataclasses.dataclass, dc), (records.record, rec)):
        class Labelled(base):  # type: ignore[valid-type, misc]
            label: str = "p"

        made.append(decorate(Labelled))
    a, b = made[0](x=1), made[1](x=1)
    assert repr(a).replace("Labelled", "") == repr(b).replace("Labelled", "")
    assert [f.name for f in dataclasses.fields(b)] == ["x", "y", "tags", "label"]
    assert b.tags == [] and b.tags is not made[1](x=1).tags
    for _ in range(records.HOT):
        made[1](1, 2, ["t"], "q")  # its own __init__ too, apart from its base's
    assert made[1](1, label="q") == made[1](x=1, y=2, tags=[], label="q")
    assert made[1].__init__ is not rec.__init__


def test_a_default_before_a_required_field_is_refused_alike() -> None:
    for decorate in (dataclasses.dataclass, records.record):
        with pytest.raises(TypeError, match="non-default argument 'y' follows default"):
            class Bad:
                x: int = 1
                y: int

            decorate(Bad)


def test_models_stay_keyword_only_frozen_and_hashable() -> None:
    for _ in range(records.HOT):  # with the model's own __init__ (and its __post_init__)
        Literal(predicate="on", args=["a"])
    assert Literal.__init__ is not records._init
    literal = Literal(predicate="on", args=["a", "b"])  # lists are stored as tuples
    assert literal.args == ("a", "b")
    assert literal == Literal(predicate="on", args=("a", "b"))
    assert hash(literal) == hash(Literal(predicate="on", args=("a", "b")))
    assert repr(literal) == "Literal(predicate='on', args=('a', 'b'), positive=True)"
    with pytest.raises(TypeError):
        Literal("on")  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        literal.positive = False  # type: ignore[misc]
    assert literal.model_copy(update={"positive": False}).positive is False


def test_models_pickle_and_keep_their_cached_properties_apart() -> None:
    from btplan.model import Problem, TypedName

    domain = Domain(name="d", types=(TypeDef(name="object", parent=None),))
    task = Task(domain=domain, problem=Problem(name="p", domain="d",
                                               objects=(TypedName(name="a"),)))
    assert task.object_types == {"a": "object"}  # cached beside the fields
    again = pickle.loads(pickle.dumps(task))
    assert again == task and hash(again) == hash(task)
    assert again.object_types == task.object_types
    assert dataclasses.asdict(domain)["types"] == ({"name": "object", "parent": None},)
