"""DOT in the paper's notation (rendered by graphviz when installed) and the rich text view."""

from __future__ import annotations

import shutil
import subprocess

import pytest
from bt_stubs import example1_world, figure7_tree

from btplan.bt import BehaviorTree, Fallback, Retry, Sequence
from btplan.bt.formats import DUMP_FORMATS, dump
from btplan.bt.formats.dot import COLOURS, dump_dot
from btplan.bt.formats.text import dump_ascii
from btplan.bt.status import FAILURE, RUNNING, SUCCESS
from btplan.bt.trace import TickRecorder


def ticked_figure7() -> tuple[BehaviorTree, dict]:  # type: ignore[type-arg]
    tree = figure7_tree()
    recorder = TickRecorder()
    recorder.attach(tree)
    tree.tick(example1_world())
    assert recorder.last is not None
    return tree, recorder.last.statuses()


def test_figure7_dot_matches_the_golden_file(golden) -> None:  # type: ignore[no-untyped-def]
    golden("bt_figure7.dot", dump_dot(figure7_tree()))


def test_dot_uses_the_paper_notation() -> None:
    text = dump_dot(figure7_tree())
    assert 'n0 [label="?", shape=box' in text
    assert 'n2 [label="→", shape=box' in text
    assert 'label="MoveTo(cube, tau_cube)", shape=box]' in text
    assert 'label="holding(cube)", shape=ellipse]' in text
    assert "n0 -> n1;" in text and "ordering=out" in text
    memory = dump_dot(BehaviorTree(Sequence([Fallback([], memory=True)], memory=True)))
    assert 'label="→*"' in memory and 'label="?*"' in memory
    assert 'label="Retry 2"' in dump_dot(BehaviorTree(Retry(Sequence([]), attempts=2)))


def test_dot_colours_the_nodes_a_tick_reached_by_status() -> None:
    tree, statuses = ticked_figure7()
    text = dump_dot(tree, statuses)
    lines = {line.split(" ")[2]: line for line in text.splitlines() if " [label=" in line}
    assert COLOURS[FAILURE] in lines["n1"] and COLOURS[RUNNING] in lines["n10"]
    assert COLOURS[SUCCESS] in lines["n9"] and "fillcolor" not in lines["n12"]


@pytest.mark.parametrize("coloured", [False, True])
def test_dot_renders_with_graphviz(coloured: bool) -> None:
    if shutil.which("dot") is None:
        pytest.skip("graphviz 'dot' is not installed (Debian: apt-get install graphviz)")
    tree, statuses = ticked_figure7()
    text = dump_dot(tree, statuses if coloured else None)
    result = subprocess.run(["dot", "-Tsvg"], input=text, capture_output=True, text=True,
                            check=False)
    assert result.returncode == 0, result.stderr
    assert result.stdout.count('class="node"') == len(tree.nodes())
    assert "MoveTo(cube, tau_cube)" in result.stdout


def test_ascii_view_matches_the_golden_file(golden) -> None:  # type: ignore[no-untyped-def]
    golden("bt_figure7.txt", dump_ascii(figure7_tree()))


def test_ascii_colours_reached_nodes_and_dims_the_rest() -> None:
    tree, statuses = ticked_figure7()
    text = dump_ascii(tree, statuses, color=True)
    moveto = next(ln for ln in text.splitlines() if "MoveTo(cube" in ln)
    assert "\x1b[33mRUNNING" in moveto
    place = next(ln for ln in text.splitlines() if "Place(cube" in ln)
    assert "\x1b[2m[Place(cube, goal)]" in place and "RUNNING" not in place
    assert "\x1b" not in dump_ascii(tree, statuses), "no escape codes unless asked"


def test_dump_knows_every_format_and_colours_by_last_status() -> None:
    tree, _ = ticked_figure7()
    assert set(DUMP_FORMATS) == {"xml", "dot", "json", "ascii"}
    assert "fillcolor" in dump(tree, "dot", with_status=True)
    assert "RUNNING" in dump(tree, "ascii", with_status=True)
    assert "fillcolor" not in dump(tree, "dot")
