"""BT.CPP v4 XML: golden export, exact re-import, and BT.CPP itself ticking every export.

The oracle test runs the exported XML in BehaviorTree.CPP (behaviortreepy) and btplan's
engine side by side on identical scripted worlds and compares, tick by tick, the root
status and every start, step and halt the leaves received.
"""

from __future__ import annotations

import random

import pytest
from bt_stubs import ScriptWorld, every_kind_root, figure7_tree, random_root

from btplan.bt import FAILURE, RUNNING, SUCCESS, Action, BehaviorTree, Condition, Sequence
from btplan.bt.formats.btcpp import ExportError, dump_xml, load_xml
from btplan.bt.formats.saved import dump_json
from btplan.errors import InputError

pytest.importorskip("behaviortreepy")
from btcpp_oracle import BtcppRun, port_free_copy

XML_HEAD = '<root BTCPP_format="4" main_tree_to_execute="Main">\n'
Change = dict[int, tuple[set[tuple[str, tuple[str, ...]]], set[tuple[str, tuple[str, ...]]]]]


def side_by_side(tree: BehaviorTree, world: ScriptWorld, other: ScriptWorld, ticks: int,
                 changes: Change | None = None) -> None:
    run = BtcppRun(dump_xml(tree), other)
    for tick in range(ticks):
        add, remove = (changes or {}).get(tick, (set(), set()))
        for w in (world, other):
            w.facts |= add
            w.facts -= remove
        ours, theirs = tree.tick(world), run.tick()
        assert (tick, ours, world.take_log()) == (tick, theirs, other.take_log())


def test_figure7_xml_matches_the_golden_file(golden) -> None:  # type: ignore[no-untyped-def]
    golden("bt_figure7.xml", dump_xml(figure7_tree()))


def test_a_hand_written_explicit_leaf_and_a_timeout_in_msec_are_read() -> None:
    text = (XML_HEAD + '<BehaviorTree ID="Main"><Timeout msec="250">'
            '<Action ID="Pick" o="cube"/></Timeout></BehaviorTree><TreeNodesModel>'
            '<Action ID="Pick"><input_port name="o"/></Action></TreeNodesModel></root>')
    tree = load_xml(text)
    assert tree.root.kind == "Timeout" and tree.root.ticks == 3  # type: ignore[attr-defined]
    assert tree.root.children[0].key == ("Pick", ("cube",))  # type: ignore[attr-defined]


@pytest.mark.parametrize("make", [figure7_tree, lambda: BehaviorTree(every_kind_root())])
def test_export_import_export_is_identical(make) -> None:  # type: ignore[no-untyped-def]
    tree = make()
    text = dump_xml(tree)
    again = load_xml(text)
    assert dump_xml(again) == text
    assert dump_json(again) == dump_json(tree)


def test_names_and_arguments_with_markup_characters_survive_the_round_trip() -> None:
    tree = BehaviorTree(Sequence([Condition("at", ('a&b "c"',), ("x",), name="<at> & 'so'"),
                                  Action("Go", ("<x>",), ("to",))], name='say "hi"'))
    text = dump_xml(tree)
    assert dump_json(load_xml(text)) == dump_json(tree)


def test_ports_in_the_export_match_the_tree_nodes_model() -> None:
    _, keys = port_free_copy(dump_xml(figure7_tree()))
    assert sorted(set(keys.values()))[:3] == [
        ("MoveTo", ("cube", "tau_cube")), ("MoveTo", ("goal", "tau_goal")), ("Pick", ("cube",))]


def test_btcpp_replays_the_cube_slipping_like_btplan() -> None:
    facts = {("hand_empty", ()), ("free", ("tau_cube",)), ("free", ("tau_goal",))}
    scripts = {"MoveTo": [RUNNING, RUNNING, SUCCESS, RUNNING, RUNNING, RUNNING, SUCCESS],
               "Pick": [RUNNING, SUCCESS], "Place": [RUNNING, SUCCESS]}
    near_cube, near_goal = ("near", ("cube",)), ("near", ("goal",))
    holding, empty = ("holding", ("cube",)), ("hand_empty", ())
    changes: Change = {
        3: ({near_cube}, set()),
        5: ({holding}, {empty}),
        7: ({empty}, {holding, near_cube}),  # the cube slips while moving to the goal
        10: ({near_cube}, set()),
        12: ({holding}, {empty}),
        14: ({near_goal}, set()),
    }
    side_by_side(figure7_tree(), ScriptWorld(facts, scripts), ScriptWorld(facts, scripts), 18,
                 changes)


def test_btcpp_ticks_every_node_kind_like_btplan() -> None:
    scripts = {"Pick": [FAILURE, RUNNING, FAILURE, SUCCESS], "Wave": [RUNNING, SUCCESS],
               "Drop": [RUNNING, SUCCESS]}
    facts = {("lit", ("lamp",))}
    changes: Change = {2: ({("hand_empty", ())}, set()), 5: (set(), {("hand_empty", ())}),
                       6: ({("near", ("goal",))}, set())}
    side_by_side(BehaviorTree(every_kind_root()), ScriptWorld(facts, scripts),
                 ScriptWorld(facts, scripts), 10, changes)


@pytest.mark.parametrize("seed", range(40))
def test_btcpp_agrees_on_random_trees(seed: int) -> None:
    rng = random.Random(seed)
    tree = BehaviorTree(random_root(rng, depth=4))
    scripts = {a: [rng.choice([RUNNING, RUNNING, SUCCESS, FAILURE]) for _ in range(30)]
               for a in ("A", "B")}
    atoms = [(p, (x,)) for p in ("p", "q") for x in ("a", "b")]
    changes: Change = {t: ({a for a in atoms if rng.random() < 0.3},
                           {a for a in atoms if rng.random() < 0.3}) for t in range(12)}
    side_by_side(tree, ScriptWorld(set(), scripts), ScriptWorld(set(), scripts), 12, changes)


def test_export_refuses_ids_btcpp_would_reject() -> None:
    with pytest.raises(ExportError, match="cannot be a BehaviorTree.CPP node ID"):
        dump_xml(BehaviorTree(Condition("at.cube")))
    with pytest.raises(ExportError, match="port"):
        dump_xml(BehaviorTree(Action("Go", ("x",), ("name",))))
    with pytest.raises(ExportError, match="one ID needs one kind"):
        dump_xml(BehaviorTree(Sequence([Condition("go"), Action("go")])))



@pytest.mark.parametrize(("body", "message", "line"), [
    ('<BehaviorTree ID="Main">\n  <Inverter/>\n</BehaviorTree>\n</root>',
     "exactly one child", 3),
    ('<BehaviorTree ID="Main">\n  <Sequence/>\n</BehaviorTree>\n</root>',
     "needs at least 1 children, not 0", 3),
    ('<BehaviorTree ID="Other"><ReactiveSequence/></BehaviorTree></root>',
     "no <BehaviorTree ID=\"Main\">", 1),
    ('<BehaviorTree ID="Main">\n  <ReactiveSequence>\n</BehaviorTree></root>',
     "not well-formed XML", 4),
    (('<BehaviorTree ID="Main">\n<RetryUntilSuccessful num_attempts="0">\n'
     '<AlwaysSuccess/></RetryUntilSuccessful></BehaviorTree></root>'),
     "num_attempts=0 is not supported", 3),
    (('<BehaviorTree ID="Main">\n<Timeout msec="soon"><AlwaysSuccess/></Timeout>\n'
     '</BehaviorTree></root>'), "msec='soon' is not a whole number", 3),
    ('<BehaviorTree ID="Main">\n<ReactiveSequence colour="red"/></BehaviorTree></root>',
     "<ReactiveSequence> has no attribute 'colour'", 3),
    (('<BehaviorTree ID="Main">\n<Pick o="a" speed="3"/></BehaviorTree>\n<TreeNodesModel>'
     '<Action ID="Pick"><input_port name="o"/></Action></TreeNodesModel></root>'),
     "Pick has no port 'speed'", 3),
    ('<root2/>', "expected <root>", 2),
])
def test_bad_xml_is_an_input_error_with_a_location(body: str, message: str, line: int) -> None:
    text = XML_HEAD + body if not body.startswith("<root2") else "<?xml version='1.0'?>\n" + body
    with pytest.raises(InputError) as info:
        load_xml(text, "tree.xml")
    assert message in info.value.message
    assert info.value.span is not None and info.value.span.line == line
