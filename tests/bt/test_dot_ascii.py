"""DOT in the paper's notation (rendered by graphviz when installed) and the rich text view."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from bt_stubs import example1_world, figure7_tree

from btplan.bt import BehaviorTree, Fallback, Retry, Sequence
from btplan.bt.formats import DUMP_FORMATS, dump, load_tree
from btplan.bt.formats.dot import COLOURS, dump_dot
from btplan.bt.formats.text import dump_ascii
from btplan.bt.status import FAILURE, RUNNING, SUCCESS
from btplan.bt.trace import TickRecorder
from btplan.errors import InputError


def ticked_figure7() -> tuple[BehaviorTree, dict]:  # type: ignore[type-arg]
    tree = figure7_tree()
    recorder = TickRecorder()
    recorder.attach(tree)
    tree.tick(example1_world())
    assert recorder.last is not None
    return tree, recorder.last.statuses()


DOCS = Path(__file__).resolve().parents[2] / "docs" / "trees"


def slipped_figure7() -> tuple[BehaviorTree, dict, tuple[str, ...]]:  # type: ignore[type-arg]
    """Figure 7 on the tick after the cube slipped mid-MoveTo (coloured in the docs)."""
    tree, world = figure7_tree(), example1_world()
    recorder = TickRecorder()
    recorder.attach(tree)
    for _ in range(5):
        tree.tick(world)
    world.facts -= {("holding", ("cube",))}
    world.facts |= {("hand_empty", ())}
    tree.tick(world)
    assert recorder.last is not None and recorder.last.halted
    return tree, recorder.last.statuses(), recorder.last.halted


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


def test_dot_outlines_the_action_a_tick_halted() -> None:
    tree, statuses, halted = slipped_figure7()
    text = dump_dot(tree, statuses, halted)
    moveto_goal = next(ln for ln in text.splitlines() if "MoveTo(goal" in ln)
    assert 'style="dashed,bold"' in moveto_goal and "halted" in moveto_goal
    assert text.count("dashed") == 1


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


def test_ascii_marks_the_action_a_tick_halted() -> None:
    tree, statuses, halted = slipped_figure7()
    lines = dump_ascii(tree, statuses, halted=halted).splitlines()
    assert [ln.strip("│├└─ ") for ln in lines if "HALTED" in ln] == [
        "[MoveTo(goal, tau_goal)] HALTED"]


def test_dump_knows_every_format_and_colours_by_last_status() -> None:
    tree, _ = ticked_figure7()
    assert set(DUMP_FORMATS) == {"xml", "dot", "json", "ascii"}
    assert "fillcolor" in dump(tree, "dot", with_status=True)
    assert "RUNNING" in dump(tree, "ascii", with_status=True)
    assert "fillcolor" not in dump(tree, "dot")


@pytest.mark.parametrize("picture", ["figure7.png", "figure7-slip.png"])
def test_docs_pictures_render_from_the_hand_built_figure7(
        picture: str, request: pytest.FixtureRequest, tmp_path: Path) -> None:
    """Renders the pictures of docs/trees.md; `--update-golden` refreshes them."""
    if shutil.which("dot") is None:
        pytest.skip("graphviz 'dot' is not installed (Debian: apt-get install graphviz)")
    if picture == "figure7.png":
        text = dump_dot(figure7_tree())
    else:
        text = dump_dot(*slipped_figure7())  # coloured, MoveTo(goal) outlined as halted
    out = tmp_path / picture
    subprocess.run(["dot", "-Tpng", "-Gdpi=110", "-o", str(out)], input=text.encode(),
                   check=True)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    if request.config.getoption("--update-golden"):
        DOCS.mkdir(parents=True, exist_ok=True)
        (DOCS / picture).write_bytes(out.read_bytes())
    assert (DOCS / picture).exists(), "run pytest --update-golden to render the docs picture"


def test_unknown_formats_are_input_errors() -> None:
    tree = figure7_tree()
    with pytest.raises(InputError, match="unknown tree format 'png'"):
        dump(tree, "png")
    with pytest.raises(InputError, match="cannot read trees in format 'dot'"):
        load_tree("digraph {}", "dot")


def test_ascii_shows_lower_case_action_names_that_look_like_markup() -> None:
    """`[pickup(a)]` must print as text, not vanish as a rich style tag."""
    from btplan.bt import Action, Condition

    tree = BehaviorTree(Sequence([Condition("clear", ("a",), ("x",)), Action("pickup", ("a",), ("x",))]))
    text = dump_ascii(tree)
    assert "[pickup(a)]" in text and "(clear(a))" in text


def test_control_characters_in_names_are_shown_as_escapes() -> None:
    """A name from a file must not drive the terminal: ESC and newlines become `\\x1b`, `\\n`."""
    from btplan.bt import Action, Condition

    tree = BehaviorTree(Fallback([Condition("on", ("cu\x1bbe", "goal")),
                                  Sequence([Action("Pick", ("cube",))],
                                           name="evil\x1b[31mred\nline")]))
    for fmt in ("ascii", "dot"):
        text = dump(tree, fmt)
        assert not any(c != "\n" and not c.isprintable() for c in text), fmt
        assert "\\x1b" in text
