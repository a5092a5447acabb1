"""Leaves and composites set Node's fields themselves (no call up to Node.__init__):
every field must still be set, to the same values Node.__init__ gives."""

from __future__ import annotations

import pytest

from btplan.bt import Action, Condition, Fallback, Node, Sequence
from btplan.bt.decorators import Inverter
from btplan.bt.leaves import leaf_label
from btplan.bt.status import IDLE


def _fields(cls: type) -> list[str]:
    return [name for klass in cls.__mro__ for name in getattr(klass, "__slots__", ())]


@pytest.mark.parametrize("make", [
    lambda: Condition("on", ("a", "b")),
    lambda: Condition("hand_empty"),
    lambda: Action("stack", ("a", "b"), ("x", "y")),
    lambda: Sequence([Condition("clear", ("a",))]),
    lambda: Fallback([], name="f"),
    lambda: Inverter(Condition("holding", ("a",))),
])
def test_every_field_of_a_new_node_is_set_as_node_sets_it(make: object) -> None:
    assert callable(make)
    node = make()
    assert isinstance(node, Node)
    for name in _fields(type(node)):
        assert hasattr(node, name), name
    assert node.status is IDLE and node.parent is None and node.origin is None
    for child in node.children:
        assert child.parent is node


def test_a_leaf_is_named_by_leaf_label_unless_named() -> None:
    assert Condition("on", ("a", "b")).name == leaf_label("on", ("a", "b")) == "on(a, b)"
    assert Condition("hand_empty").name == leaf_label("hand_empty", ()) == "hand_empty"
    assert Action("pick", ("a",), name="grab").name == "grab"
    with pytest.raises(ValueError, match="1 port names for 2 arguments"):
        Condition("on", ("a", "b"), ("x",))
