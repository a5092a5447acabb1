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
