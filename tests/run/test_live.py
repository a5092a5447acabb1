"""The live view's frames: the tree with this tick's statuses, changed facts, disturbances."""

from __future__ import annotations

from rich.console import Console

from btplan.acting.live_view import LiveView, frame
from btplan.acting.records import ExpansionNote, TickRecord
from btplan.bt import FAILURE, RUNNING, Action, Condition, Fallback, Sequence
from btplan.worlds.agents import Disturbance


def text_of(renderable: object) -> str:
    console = Console(width=100, record=True, color_system=None)
    console.print(renderable)
    return console.export_text()


def tree() -> tuple[Sequence, Condition, Action]:
    holding = Condition("holding", ("cube",))
    pick = Action("Pick", ("cube",))
    root = Sequence([Fallback([holding, Sequence([pick])])])
    return root, holding, pick


def test_a_frame_shows_the_tree_statuses_facts_and_disturbances() -> None:
    root, holding, pick = tree()
    record = TickRecord(
        tick=7, status="RUNNING", added=("hand_empty()",), removed=("holding(cube)",),
        disturbances=(Disturbance(7, "undo@7", "undid Pick(cube)", "undo"),),
        expansions=(ExpansionNote("near(cube)", ("MoveTo(cube, t)",), 0, 0),),
    )
    text = text_of(frame(root, {id(holding): FAILURE, id(pick): RUNNING}, record,
                         list(record.disturbances), expansions=3))
    assert "tick 7  RUNNING   expansions 3   (grew at near(cube))" in text
    assert "(holding(cube))  FAILURE" in text
    assert "[Pick(cube)]  RUNNING" in text
    assert "→" in text and "?" in text
    assert "+hand_empty()" in text and "-holding(cube)" in text
    assert "undo@7" in text and "undid Pick(cube)" in text


def test_nodes_added_since_the_last_frame_are_marked_new() -> None:
    root, _, pick = tree()
    old = frozenset(id(n) for n in root.walk() if n is not pick)
    text = text_of(frame(root, {}, TickRecord(tick=1, status="FAILURE"), [], old))
    assert "[Pick(cube)]  new" in text
    assert "(holding(cube))  new" not in text


def test_the_live_view_draws_each_tick_on_its_console() -> None:
    root, holding, pick = tree()
    console = Console(width=100, record=True, color_system=None, force_terminal=False)
    with LiveView(console) as live:
        live.show(root, {id(holding): FAILURE}, TickRecord(tick=1, status="FAILURE"))
        live.show(root, {id(pick): RUNNING}, TickRecord(tick=2, status="RUNNING"))
    assert "tick 2  RUNNING" in console.export_text()


def test_a_negated_condition_is_one_line_with_the_inverters_own_status() -> None:
    from btplan.bt.decorators import Inverter

    blocked = Condition("blocks", ("_", "t"))
    guard = Inverter(blocked)
    root = Sequence([guard, Action("MoveTo", ("goal", "t"))])
    text = text_of(frame(root, {id(guard): FAILURE, id(blocked): RUNNING}, TickRecord(
        tick=3, status="FAILURE"), []))
    assert "(not blocks(_, t))  FAILURE" in text
    assert "(blocks(_, t))" not in text.replace("(not blocks(_, t))", "")


def test_a_tree_taller_than_the_terminal_keeps_the_facts_and_shows_the_running_branch() -> None:
    ran = Action("Run", ())
    idle = [Sequence([Condition("c", (str(i),)), Action("A", (str(i),))]) for i in range(30)]
    root = Fallback([*idle[:15], Sequence([ran]), *idle[15:]])
    record = TickRecord(tick=9, status="RUNNING", added=("moved()",))
    text = text_of(frame(root, {id(root): RUNNING, id(root.children[15]): RUNNING,
                                id(ran): RUNNING}, record, [], rows=20))
    lines = text.splitlines()
    assert lines[1].startswith("facts: +moved()")  # above the tree: never cut off
    assert "[Run]  RUNNING" in text
    assert "… 45 not reached" in text and len(lines) < 20
