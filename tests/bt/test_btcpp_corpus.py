"""A corpus of trees in the styles real projects write them, read, written back node for
node, and ticked in BehaviorTree.CPP beside btplan's engine.

Each tree is read with btplan (includes, palette, version 3 as needed) and exported;
the export must hold the same trees node for node as the input (compared here with
ElementTree, independently of btplan's reader), declare every custom node, read back
to the same text, draw as DOT, and -- unless it holds custom controls, which only C++
can define -- load into BT.CPP and tick there exactly as in btplan: the root status,
every start, step and halt the leaves receive, and the final root blackboard.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from bt_stubs import ScriptWorld

from btplan.bt import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.blackboard import NodeError, as_text
from btplan.bt.formats import dump
from btplan.bt.formats.btcpp import dump_xml, load_xml
from btplan.bt.formats.btcpp_catalog import BUILTINS, EXPLICIT_TAGS

pytest.importorskip("behaviortreepy")
from btcpp_oracle import UNREADABLE, BtcppDocRun

CORPUS = Path(__file__).parent / "corpus"
LeafKey = tuple[str, tuple[str, ...]]


@dataclass
class Case:
    file: str
    ticks: int = 0  # 0: not tickable in BT.CPP (custom controls)
    models: tuple[str, ...] = ()
    same_as: str = ""  # a hand-written v4 file the export must match (version 3 input)
    facts: set[LeafKey] = field(default_factory=set)
    scripts: dict[str, list[Status]] = field(default_factory=dict)
    changes: dict[int, tuple[set[LeafKey], set[LeafKey]]] = field(default_factory=dict)
    ends: Status | None = None


CASES = [
    Case("scripts.xml", 24, scripts={
        "Charge": [RUNNING, SUCCESS], "Vacuum": [RUNNING, SUCCESS, SUCCESS, FAILURE, SUCCESS],
        "Mop": [SUCCESS], "Blink": [RUNNING, RUNNING, SUCCESS, RUNNING, SUCCESS]},
        ends=SUCCESS),
    Case("nav_stack.xml", 30, models=("nav_palette.xml",), scripts={
        "ComputePathToPose": [RUNNING, SUCCESS], "FollowPath": [RUNNING, RUNNING, FAILURE,
                                                                RUNNING, RUNNING],
        "ClearEntireCostmap": [SUCCESS], "BackUp": [RUNNING, SUCCESS], "Spin": [RUNNING, SUCCESS],
        "Wait": [SUCCESS]},
        facts={("GoalUpdated", ())},
        changes={3: (set(), {("GoalUpdated", ())}), 6: ({("IsStuck", ())}, set()),
                 14: ({("GoalReached", ("{goal}",))}, set())}, ends=SUCCESS),
    Case("nav_recovery.xml", models=("nav_palette.xml",)),
    Case("groot_v3.xml", 12, same_as="groot_v3.v4.xml", scripts={
        "GoTo": [RUNNING, SUCCESS, FAILURE, RUNNING, SUCCESS], "Latch": [RUNNING, SUCCESS]},
        changes={2: ({("AtPlace", ("dock",))}, set())}, ends=SUCCESS),
    Case("includes/main.xml", 16, scripts={
        "Move": [RUNNING, SUCCESS], "Grasp": [RUNNING, SUCCESS], "Release": [SUCCESS]},
        changes={2: ({("At", ("shelf",))}, set()), 5: ({("At", ("office",))}, set())},
        ends=SUCCESS),
]


def _document(path: Path) -> tuple[dict[str, ET.Element], dict[str, str]]:
    """Trees and declared kinds of a file and everything it includes."""
    root = ET.parse(path).getroot()
    trees = {t.attrib["ID"]: t for t in root.findall("BehaviorTree")}
    kinds = {e.attrib["ID"]: e.tag for m in root.findall("TreeNodesModel") for e in m}
    for include in root.findall("include"):
        more_trees, more_kinds = _document(path.parent / include.attrib["path"])
        trees.update(more_trees)
        kinds.update(more_kinds)
    return trees, kinds


def _shape(element: ET.Element) -> tuple[object, ...]:
    explicit = element.tag in EXPLICIT_TAGS
    ident = element.attrib["ID"] if explicit else element.tag
    attrs = sorted((k, v) for k, v in element.attrib.items() if not (explicit and k == "ID"))
    return ident, attrs, [_shape(child) for child in element]


def _idents(element: ET.Element) -> set[str]:
    return {(e.attrib["ID"] if e.tag in EXPLICIT_TAGS else e.tag) for e in element.iter()}


def _load(case: Case):  # type: ignore[no-untyped-def]
    path = CORPUS / case.file
    models = [((CORPUS / m).read_text(), str(CORPUS / m)) for m in case.models]
    return load_xml(path.read_text(), str(path), models)


@pytest.mark.parametrize("case", CASES, ids=[c.file for c in CASES])
def test_the_export_holds_the_same_trees_node_for_node(case: Case) -> None:
    out = dump_xml(_load(case))
    exported = ET.fromstring(out)
    assert exported.attrib["BTCPP_format"] == "4"
    trees, kinds = _document(CORPUS / (case.same_as or case.file))
    for model in case.models:
        kinds.update(_document(CORPUS / model)[1])
    written = {t.attrib["ID"]: t for t in exported.findall("BehaviorTree")}
    assert sorted(written) == sorted(trees)
    for ident, tree in trees.items():
        assert [_shape(c) for c in written[ident]] == [_shape(c) for c in tree], ident
    declared = {e.attrib["ID"]: e.tag for e in exported.find("TreeNodesModel") or []}
    used = set().union(*(_idents(t) for t in trees.values())) - set(BUILTINS) - {"BehaviorTree"}
    assert used <= set(declared)
    assert {i: declared[i] for i in used if i in kinds} == {i: kinds[i] for i in used if i in kinds}
    assert dump_xml(load_xml(out)) == out
    assert dump(load_xml(out), "dot").startswith("digraph")


def _number_or_text(value: str) -> object:
    try:
        return round(float(value), 6)
    except ValueError:
        return value


@pytest.mark.parametrize("case", [c for c in CASES if c.ticks], ids=lambda c: c.file)
def test_btcpp_ticks_the_export_like_btplan(case: Case) -> None:
    tree = _load(case)
    ours, theirs = ScriptWorld(case.facts, case.scripts), ScriptWorld(case.facts, case.scripts)
    run = BtcppDocRun(dump_xml(tree), theirs)
    statuses = []
    for tick in range(case.ticks):
        add, remove = case.changes.get(tick, (set(), set()))
        for world in (ours, theirs):
            world.facts |= add
            world.facts -= remove
        mine, other = tree.tick(ours), run.tick()
        assert (tick, mine, ours.take_log()) == (tick, other, theirs.take_log())
        statuses.append(mine)
    assert case.ends is None or case.ends in statuses
    assert tree.imported is not None
    board = {k: _number_or_text(as_text(float(v) if isinstance(v, bool) else v))
             for k, v in tree.imported.board.snapshot().items()}
    assert board == {k: _number_or_text(v) for k, v in run.board().items() if v != UNREADABLE}


def test_a_custom_control_is_drawn_and_converted_but_not_ticked() -> None:
    tree = _load(CASES[2])
    with pytest.raises(NodeError, match="RecoveryNode is a custom control"):
        tree.tick(ScriptWorld())
