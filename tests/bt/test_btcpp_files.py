"""Reading BT.CPP XML as people have it: undeclared nodes, palettes, several trees,
includes, version 3 files."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.bt.formats.btcpp import dump_xml, load_xml
from btplan.errors import InputError

HEAD = '<root BTCPP_format="4">\n'


def test_undeclared_nodes_are_inferred_from_their_shape_with_one_warning_each() -> None:
    text = HEAD + ('<BehaviorTree ID="T">\n<Guarded>\n<Pipeline>\n<Spin angle="1"/>'
                   '<Spin angle="2"/>\n</Pipeline>\n</Guarded>\n</BehaviorTree>\n</root>')
    tree = load_xml(text, "t.xml")
    assert tree.imported is not None
    models = tree.imported.doc.models
    assert [(i, models[i].kind) for i in ("Guarded", "Pipeline", "Spin")] == [
        ("Guarded", "Decorator"), ("Pipeline", "Control"), ("Spin", "Action")]
    warnings = tree.imported.doc.warnings
    assert len([w for w in warnings if "Spin is not declared" in w]) == 1
    assert "t.xml:5:1: Spin is not declared; read as an action" in "\n".join(warnings)


def test_strict_refuses_an_undeclared_node_with_a_hint() -> None:
    text = HEAD + '<BehaviorTree ID="T">\n<Sequence><Invertr><Foo/></Invertr></Sequence>' \
        '</BehaviorTree></root>'
    with pytest.raises(InputError, match="unknown node <Invertr>") as info:
        load_xml(text, "t.xml", strict=True)
    assert info.value.hint == "did you mean 'Inverter'?"


def test_a_palette_declares_kinds_and_ports_and_the_file_model_wins() -> None:
    palette = ('<root BTCPP_format="4"><TreeNodesModel>'
               '<Condition ID="IsBatteryLow"><input_port name="min"/></Condition>'
               '<Action ID="Spin"><input_port name="angle"/>'
               '<output_port name="done"/></Action></TreeNodesModel></root>')
    text = HEAD + ('<BehaviorTree ID="T"><Fallback><IsBatteryLow min="0.2"/>'
                   '<Spin angle="1"/></Fallback></BehaviorTree>'
                   '<TreeNodesModel><Condition ID="Spin"/></TreeNodesModel></root>')
    with pytest.raises(InputError, match="Spin has no port 'angle'"):
        load_xml(text, "t.xml", models=[(palette, "nav.xml")])
    tree = load_xml(text.replace('<Condition ID="Spin"/>', ""), "t.xml",
                    models=[(palette, "nav.xml")])
    assert [n.kind for n in tree.root.children] == ["Condition", "Action"]
    assert tree.imported is not None and not tree.imported.doc.warnings
    out = dump_xml(tree)
    assert '<output_port name="done"/>' in out and 'ID="IsBatteryLow"' in out


def test_a_model_file_without_tree_nodes_model_is_refused() -> None:
    with pytest.raises(InputError, match="no <TreeNodesModel>") as info:
        load_xml(HEAD + '<BehaviorTree ID="T"><AlwaysSuccess/></BehaviorTree></root>', "t.xml",
                 models=[("<root/>", "empty.xml")])
    assert info.value.span is not None and info.value.span.path == "empty.xml"


def test_declared_ports_may_be_left_out_and_outputs_are_understood() -> None:
    text = HEAD + ('<BehaviorTree ID="T"><Plan goal="{g}"/></BehaviorTree><TreeNodesModel>'
                   '<Action ID="Plan"><input_port name="goal"/><input_port name="planner" '
                   'default="grid"/><output_port name="path"/></Action></TreeNodesModel></root>')
    assert load_xml(text).root.kind == "Action"


SEVERAL = HEAD + ('<BehaviorTree ID="A"><SubTree ID="B"/></BehaviorTree>\n'
                  '<BehaviorTree ID="B"><AlwaysSuccess/></BehaviorTree>\n'
                  '<BehaviorTree ID="C"><AlwaysFailure/></BehaviorTree></root>')


def test_the_tree_to_execute_is_given_or_the_only_one_no_subtree_calls() -> None:
    with pytest.raises(InputError, match="several trees and no main_tree_to_execute") as info:
        load_xml(SEVERAL)
    assert info.value.hint == "choose one with --tree: A, B, C"
    assert load_xml(SEVERAL, tree_id="C").name == "C"
    assert load_xml(SEVERAL.replace('<BehaviorTree ID="C"><AlwaysFailure/></BehaviorTree>', "")
                    ).name == "A"
    with pytest.raises(InputError, match="no <BehaviorTree ID=\"D\">"):
        load_xml(SEVERAL, tree_id="D")


def test_includes_are_relative_to_the_including_file_and_cycles_are_refused(
        tmp_path: Path) -> None:
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "moves.xml").write_text(
        HEAD + '<include path="more.xml"/><BehaviorTree ID="Move"><Go/></BehaviorTree>'
        '<TreeNodesModel><Action ID="Go"/></TreeNodesModel></root>')
    (tmp_path / "lib" / "more.xml").write_text(
        HEAD + '<BehaviorTree ID="Wait"><Sleep msec="200"/></BehaviorTree></root>')
    main = tmp_path / "main.xml"
    text = HEAD + ('<include path="lib/moves.xml"/>\n<BehaviorTree ID="Main"><Sequence>'
                   '<SubTree ID="Move"/><SubTree ID="Wait"/></Sequence></BehaviorTree></root>')
    tree = load_xml(text, str(main), tree_id="Main")
    assert tree.imported is not None and list(tree.imported.doc.trees) == ["Wait", "Move", "Main"]
    assert not tree.imported.doc.warnings
    assert '<Action ID="Go"/>' in dump_xml(tree)
    (tmp_path / "lib" / "more.xml").write_text(HEAD + '<include path="../main.xml"/></root>')
    with pytest.raises(InputError, match="makes a cycle") as info:
        load_xml(text, str(main), tree_id="Main")
    assert info.value.hint == "main.xml -> moves.xml -> more.xml -> main.xml"
    with pytest.raises(InputError, match="cannot include 'nowhere.xml': no such file") as info:
        load_xml(HEAD + '<include path="nowhere.xml"/></root>', str(main))
    assert info.value.span is not None and info.value.span.line == 2


def test_a_subtree_that_calls_itself_is_refused() -> None:
    text = HEAD + ('<BehaviorTree ID="A"><Sequence><SubTree ID="B"/></Sequence></BehaviorTree>'
                   '<BehaviorTree ID="B"><SubTree ID="A"/></BehaviorTree></root>')
    with pytest.raises(InputError, match="SubTree A calls itself") as info:
        load_xml(text, tree_id="A")
    assert info.value.hint == "A -> B -> A"


V3 = ('<root main_tree_to_execute="Main">\n'
      '<BehaviorTree ID="Main">\n'
      '  <SequenceStar name="steps">\n'
      '    <SubTree ID="Sub" __shared_blackboard="true"/>\n'
      '    <SubTreePlus ID="Sub" __autoremap="false" target="{goal}"/>\n'
      '    <SubTree ID="Sub" target="goal"/>\n'
      '    <RetryUntilSuccesful num_attempts="2"><AlwaysFailure/></RetryUntilSuccesful>\n'
      '    <Parallel success_threshold="1" failure_threshold="1"><AlwaysSuccess/></Parallel>\n'
      '  </SequenceStar>\n'
      '</BehaviorTree>\n'
      '<BehaviorTree ID="Sub"><AlwaysSuccess/></BehaviorTree>\n'
      '</root>')


def test_version_3_is_read_with_the_converter_renames_and_written_as_version_4() -> None:
    tree = load_xml(V3, "old.xml")
    assert tree.imported is not None
    assert "old.xml:1:1: no BTCPP_format" in tree.imported.doc.warnings[0]
    out = dump_xml(tree)
    assert '<root BTCPP_format="4" main_tree_to_execute="Main">' in out
    for line in ('<SequenceWithMemory name="steps">', '<SubTree ID="Sub" _autoremap="1"/>',
                 '<SubTree ID="Sub" _autoremap="false" target="{goal}"/>',
                 '<SubTree ID="Sub" target="{goal}"/>',
                 '<RetryUntilSuccessful num_attempts="2">',
                 '<Parallel success_count="1" failure_count="1">'):
        assert line in out
    assert dump_xml(load_xml(out)) == out


def test_an_unknown_format_version_is_refused() -> None:
    with pytest.raises(InputError, match="BTCPP_format='5' is not 3 or 4"):
        load_xml('<root BTCPP_format="5"><BehaviorTree ID="T"><AlwaysSuccess/></BehaviorTree>'
                 '</root>')


def test_scripting_enums_are_given_by_the_caller_as_bt_cpp_registers_them_in_cpp() -> None:
    text = HEAD + ('<BehaviorTree ID="T"><Sequence><Script code="c := GREEN"/>'
                   '<Switch2 variable="{c}" case_1="RED" case_2="GREEN"><AlwaysFailure/>'
                   '<AlwaysSuccess/><AlwaysFailure/></Switch2>'
                   '<ScriptCondition code="c == GREEN &amp;&amp; RED &lt; c"/></Sequence>'
                   '</BehaviorTree></root>')
    tree = load_xml(text, enums={"RED": 1, "GREEN": 2})
    assert tree.tick(None).value == "SUCCESS"  # type: ignore[arg-type]


def test_an_explicit_id_that_cannot_be_a_tag_is_refused() -> None:
    with pytest.raises(InputError, match="ID='a b' cannot be written as a tag"):
        load_xml(HEAD + '<BehaviorTree ID="T"><Action ID="a b"/></BehaviorTree></root>')


def test_a_script_that_does_not_parse_points_at_the_node_and_character() -> None:
    text = HEAD + ('<BehaviorTree ID="T">\n  <AlwaysSuccess _skipIf="x := "/>\n'
                   '</BehaviorTree></root>')
    with pytest.raises(InputError, match="in _skipIf: expected a value") as info:
        load_xml(text, "t.xml")
    assert info.value.span is not None and (info.value.span.line, info.value.span.column) == (3, 3)
    assert info.value.hint == "at character 6 of 'x := '"


def test_try_catch_runs_the_catch_block_after_a_failure() -> None:
    from bt_stubs import ScriptWorld

    from btplan.bt import FAILURE, RUNNING, SUCCESS

    text = HEAD + ('<BehaviorTree ID="T"><TryCatch><A/><B/><Clean/></TryCatch></BehaviorTree>'
                   '<TreeNodesModel><Action ID="A"/><Action ID="B"/><Action ID="Clean"/>'
                   '</TreeNodesModel></root>')
    tree = load_xml(text)
    world = ScriptWorld((), {"A": [SUCCESS], "B": [RUNNING, FAILURE, SUCCESS],
                             "Clean": [RUNNING, SUCCESS]})
    assert [tree.tick(world) for _ in range(5)] == [RUNNING, RUNNING, FAILURE, SUCCESS, SUCCESS]
    assert world.log[:5] == [("start", "A()"), ("start", "B()"), ("step", "B()"),
                             ("start", "Clean()"), ("step", "Clean()")]
