"""Tick traces: nodes reached in order with statuses, actions started and halted, JSON lines."""

from __future__ import annotations

import io
import json
from pathlib import Path

from bt_stubs import ScriptWorld, example1_world, figure7_tree

from btplan.bt import FAILURE, RUNNING, SUCCESS, Action, BehaviorTree, Condition, Sequence
from btplan.bt.composites import Sequence as PlainSequence
from btplan.bt.trace import TickRecorder, node_ids, traces_to_jsonl, write_jsonl


def test_first_tick_of_figure7_reaches_nodes_depth_first_and_starts_moveto() -> None:
    tree, world = figure7_tree(), example1_world()
    recorder = TickRecorder()
    recorder.attach(tree)
    tree.tick(world)
    trace = recorder.last
    assert trace is not None and trace.tick == 1 and trace.status is RUNNING
    assert [(n.id, n.name, n.status) for n in trace.nodes if n.kind != "Fallback"
            and n.kind != "Sequence"] == [
        ("n1", "on(cube, goal)", FAILURE),
        ("n4", "holding(cube)", FAILURE),
        ("n7", "near(cube)", FAILURE),
        ("n9", "free(tau_cube)", SUCCESS),
        ("n10", "MoveTo(cube, tau_cube)", RUNNING),
    ]
    assert trace.nodes[0].id == "n0" and trace.nodes[0].status is RUNNING
    assert trace.started == ("n10",) and trace.halted == ()


def test_slip_trace_names_the_halted_moveto_and_the_restarted_one() -> None:
    tree, world = figure7_tree(), example1_world()
    TickRecorder().attach(tree)
    for _ in range(5):
        tree.tick(world)
    world.facts -= {("holding", ("cube",))}
    world.facts |= {("hand_empty", ())}
    tree.tick(world)
    assert tree.recorder is not None and tree.recorder.last is not None
    ids = node_ids(tree.root)
    by_name = {n.name: ids[id(n)] for n in tree.nodes()}
    last = tree.recorder.last
    assert last.halted == (by_name["MoveTo(goal, tau_goal)"],)
    assert last.started == (by_name["MoveTo(cube, tau_cube)"],)
    assert len(tree.recorder.traces) == 6


def test_recording_does_not_change_what_the_tree_does() -> None:
    plain_tree, plain_world = figure7_tree(), example1_world()
    traced_tree, traced_world = figure7_tree(), example1_world()
    TickRecorder().attach(traced_tree)
    for _ in range(8):
        assert plain_tree.tick(plain_world) is traced_tree.tick(traced_world)
    assert plain_world.log == traced_world.log


def test_plain_classes_between_ticks_and_nodes_added_later_are_traced() -> None:
    seq = Sequence([Condition("a")])
    tree = BehaviorTree(seq)
    recorder = TickRecorder()
    recorder.attach(tree)
    world = ScriptWorld(facts={("a", ())})
    tree.tick(world)
    seq.append(Action("B"))  # the planner grows the tree while acting
    tree.tick(world)
    assert [n.id for n in recorder.traces[-1].nodes] == ["n0", "n1", "n2"]
    assert type(seq) is PlainSequence, "between ticks a recorded tree has its plain classes"
    recorder.detach(tree)
    assert tree.tick(world) is RUNNING and len(recorder.traces) == 2


def test_untraced_tree_keeps_plain_classes() -> None:
    tree = figure7_tree()
    tree.tick(example1_world())
    assert type(tree.root).__mro__[1].__name__ == "_Control"


def test_jsonl_has_one_parsable_line_per_tick_and_a_sink_streams_them() -> None:
    sink = io.StringIO()
    tree, world = figure7_tree(), example1_world()
    recorder = TickRecorder(keep=2, sink=sink)
    recorder.attach(tree)
    for _ in range(7):
        tree.tick(world)
    lines = sink.getvalue().splitlines()
    assert len(lines) == 7 and len(recorder.traces) == 2
    last = json.loads(lines[-1])
    assert last["tick"] == 7 and last["status"] == "SUCCESS"
    assert last["nodes"][0] == {"id": "n0", "kind": "Fallback", "name": "", "status": "SUCCESS"}
    assert traces_to_jsonl(recorder.traces).splitlines() == lines[-2:]


def test_a_trace_file_holds_one_json_object_per_tick(tmp_path: Path) -> None:
    tree, world = figure7_tree(), example1_world()
    recorder = TickRecorder()
    recorder.attach(tree)
    for _ in range(3):
        tree.tick(world)
    path = tmp_path / "trace.jsonl"
    write_jsonl(str(path), recorder.traces)
    rows = [json.loads(line) for line in path.read_text(encoding="utf-8").splitlines()]
    assert [r["tick"] for r in rows] == [1, 2, 3]
    assert rows[0]["started"] == ["n10"] and rows[2]["started"] == ["n12"]  # Pick
