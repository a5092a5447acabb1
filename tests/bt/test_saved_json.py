"""Saved-tree JSON: exact round trips, the schema, and located errors on bad input."""

from __future__ import annotations

import json
import random

import pytest
from bt_stubs import ScriptWorld, every_kind_root, figure7_tree, random_root
from hypothesis import example, given, settings
from hypothesis import strategies as st

from btplan.bt import Action, BehaviorTree, Condition, Sequence
from btplan.bt.formats.saved import dump_json, json_schema, load_json, to_model
from btplan.bt.formats.saved_out import tree_data
from btplan.errors import InputError


def test_figure7_json_matches_the_golden_file(golden) -> None:  # type: ignore[no-untyped-def]
    golden("bt_figure7.json", dump_json(figure7_tree()))


def test_every_kind_round_trips_exactly_with_statuses() -> None:
    tree = BehaviorTree(every_kind_root(), name="Kinds")
    tree.tick(ScriptWorld(facts={("hand_empty", ())}))
    text = dump_json(tree, with_status=True)
    assert '"status": "RUNNING"' in text and '"attempts": 3' in text
    again = load_json(text)
    assert dump_json(again, with_status=True) == text
    assert to_model(again, with_status=True) == to_model(tree, with_status=True)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000))
def test_random_trees_round_trip(seed: int) -> None:
    tree = BehaviorTree(random_root(random.Random(seed)))
    text = dump_json(tree)
    assert dump_json(load_json(text)) == text


def test_schema_describes_the_node_fields() -> None:
    schema = json.loads(json_schema())
    node = schema["$defs"]["SavedNode"]
    assert {"type", "ident", "args", "ports", "memory", "children", "status"} <= set(
        node["properties"])
    assert schema["required"] == ["format", "version", "root"]


def test_bad_json_syntax_points_at_the_line(tmp_path: object) -> None:
    with pytest.raises(InputError) as info:
        load_json('{\n  "format": "btplan-tree",\n  "root": {,}\n}', "t.json")
    assert (info.value.span.line, info.value.span.column) == (3, 12)  # type: ignore[union-attr]
    assert "not valid JSON" in info.value.message


def test_wrong_field_points_at_the_value() -> None:
    text = dump_json(figure7_tree()).replace('"ident": "Pick"', '"ident": 5')
    with pytest.raises(InputError) as info:
        load_json(text, "t.json")
    error = info.value
    assert error.span is not None and error.source_line is not None
    assert '"ident": 5' in error.source_line
    assert error.source_line[error.span.column - 1:].startswith("5")
    assert "ident" in error.message


def test_a_decorator_needs_one_child() -> None:
    text = ('{"format": "btplan-tree", "version": 1,\n'
            ' "root": {"type": "Inverter", "children": []}}')
    with pytest.raises(InputError, match="exactly one child") as info:
        load_json(text, "t.json")
    assert info.value.span is not None and info.value.span.line == 2


def test_unknown_node_type_is_refused() -> None:
    with pytest.raises(InputError, match="root.type"):
        load_json('{"format": "btplan-tree", "version": 1, "root": {"type": "Selector"}}')


def _reference(value: object, indent: str = "") -> str:
    """The layout written with `json` alone: indented, short lists on one line."""
    inner = indent + "  "
    if isinstance(value, dict) and value:
        items = [f"{inner}{json.dumps(k)}: {_reference(v, inner)}" for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + indent + "}"
    if isinstance(value, list) and any(isinstance(v, (dict, list)) for v in value):
        return "[\n" + ",\n".join(inner + _reference(v, inner) for v in value) + "\n" + indent + "]"
    return json.dumps(value, ensure_ascii=False)


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10_000), st.lists(st.text(st.sampled_from('ab"\\\n\x00\x7f\u00e9\u2028 '),
                                               min_size=1, max_size=6),
                                       min_size=4, max_size=4))
@example(0, ['a"b', "c\\d", "e\nf", "\u00e9\x7f"])
def test_the_writer_lays_out_what_json_would(seed: int, words: list[str]) -> None:
    """Names, idents and arguments with quotes, backslashes, control and non-ASCII
    characters are escaped as `json` escapes them; statuses and every kind of node."""
    ident, arg, port, name = words
    root = Sequence([random_root(random.Random(seed)), Condition(ident, (arg, "b"), (port, "y")),
                     Action(ident, (), None, name=name)], memory=True)
    tree = BehaviorTree(root, name=name)
    tree.tick(ScriptWorld(facts={("p", ("a",))}))
    for with_status in (False, True):
        text = dump_json(tree, with_status)
        assert text == _reference(tree_data(tree, with_status)) + "\n"
        assert json.loads(text) == tree_data(tree, with_status)
