"""The four reactive properties of the paper's Problem 1, checked on the run's trace.

Each test first runs the task undisturbed, reads from that trace when to disturb
(so the tests do not hard-code tick numbers of the planner), then runs it again with
an external agent and asserts which actions ran, which were halted, and that the
tree grew only where the property says it may.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from btplan.acting.offline import load
from btplan.acting.online import RunOutcome, run
from btplan.acting.records import TickRecord
from btplan.bt import Action, Node, Status

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK_PLACE = load(str(DOMAINS / "pick_place.bt"))


def first_tick(records: list[TickRecord], field: str, action: str) -> int:
    return next(r.tick for r in records if action in getattr(r, field))


def expanded(result: RunOutcome) -> list[str]:
    return [e.condition for _, e in result.summary().expansions]


def expansions_from(result: RunOutcome, tick: int) -> list[str]:
    return [e.condition for t, e in result.summary().expansions if t >= tick]


def shape(result: RunOutcome) -> list[tuple[str, str]]:
    """The final tree as (kind, name) in depth-first order."""
    return [(n.kind, n.name) for n in result.tree.nodes()]


def test_undo_the_robot_picks_the_cube_again_without_expanding() -> None:
    """Property 1: the cube is taken from the hand just before Place; the robot fetches it again."""
    calm = run(PICK_PLACE)
    at = first_tick(calm.records, "finished", "MoveTo(goal, tau_goal)") + 1
    result = run(PICK_PLACE, disturb=[f"undo:Pick@{at}"])
    assert result.reached
    total = result.summary()
    assert [(d.tick, d.kind) for d in total.disturbances] == [(at, "undo")]
    assert result.records[at - 1].removed == ("holding(cube)",)
    assert total.finished == [
        "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)",
        "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)", "Place(cube, goal)"]
    assert expansions_from(result, at) == []
    assert expanded(result) == expanded(calm)
    assert shape(result) == shape(calm)


def test_help_pick_and_its_move_are_skipped_without_expanding() -> None:
    """Property 2: while the robot moves to the cube, someone puts the cube in its hand."""
    calm = run(PICK_PLACE)
    at = first_tick(calm.records, "started", "MoveTo(cube, tau_cube)") + 1
    result = run(PICK_PLACE, disturb=[f"help:Pick(cube)@{at}"])
    assert result.reached
    total = result.summary()
    assert total.halted == ["MoveTo(cube, tau_cube)"]
    assert "Pick(cube)" not in total.started
    assert total.finished == ["MoveTo(goal, tau_goal)", "Place(cube, goal)"]
    assert set(expanded(result)) <= set(expanded(calm))
    assert len(expanded(result)) <= len(expanded(calm))
    assert "holding(cube)" not in expansions_from(result, at)
    assert len(result.tree.nodes()) <= len(calm.tree.nodes())


def test_alternatives_the_second_achiever_runs_when_the_first_fails() -> None:
    """Property 3: Drive keeps failing, so the Fallback's second option, Fly, delivers."""
    task = load(str(DOMAINS / "run_alternatives.bt"))
    calm = run(task)
    assert [a.name for a in calm.executed] == ["Load", "Drive"]
    result = run(task, disturb=["fail:Drive@1.."])
    assert result.reached
    total = result.summary()
    assert "Drive(box)" in total.failed
    assert [str(a) for a in result.executed] == ["Load(box)", "Fly(box)"]
    assert expanded(result) == expanded(calm)
    fallback = next(n for n in result.tree.nodes()
                    if any(isinstance(c, Action) for d in n.children for c in d.children))
    assert [c.children[-1].name for c in fallback.children[1:]] == ["Drive(box)", "Fly(box)"]


def test_runtime_expansion_a_blocked_path_grows_the_tree_on_the_fly() -> None:
    """Property 4 (the paper's Example 2): the path to the goal gets blocked while the robot
    carries the cube; the tree grows by a subtree that picks the sphere and places it
    aside, moved before the cube is picked to resolve the conflict on the hand, and the
    goal is still reached."""
    task = load(str(DOMAINS / "pick_place_obstacle.bt"))
    calm = run(task)
    at = first_tick(calm.records, "finished", "Pick(cube)") + 1
    seen: dict[int, frozenset[int]] = {}

    def remember(root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
        seen[record.tick] = frozenset(id(n) for n in root.walk())

    result = run(task, disturb=[f"set:blocks(sphere, tau_goal)@{at}"], view=remember)
    assert result.reached
    total = result.summary()
    assert [d.description for d in total.disturbances] == ["set blocks(sphere, tau_goal)"]
    grown = [(t, e) for t, e in total.expansions if t >= at]
    assert grown[0][0] == at
    assert grown[0][1].condition == "not blocks(_, tau_goal)"
    assert grown[0][1].achievers == ("Place(sphere, aside)",)
    assert grown[0][1].conflicts_resolved >= 1 and grown[0][1].moves >= 1
    # The order of the later expansions is the look-ahead's (docs/robot.md): the same five
    # conditions, each once.
    assert sorted(e.condition for _, e in grown) == sorted([
        "not blocks(_, tau_goal)", "holding(sphere)", "near(sphere)", "hand_empty()",
        "near(aside)"])
    done_after = [a for r in result.records if r.tick >= at for a in r.finished]
    assert done_after == ["MoveTo(sphere, tau_sphere)", "Drop(cube)", "Pick(sphere)",
                          "MoveTo(aside, tau_aside)", "Place(sphere, aside)",
                          "MoveTo(cube, tau_cube)", "Pick(cube)", "MoveTo(goal, tau_goal)",
                          "Place(cube, goal)"]
    # Never rebuilt: every node of the tree before the obstruction is still in the final tree.
    final = frozenset(id(n) for n in result.tree.nodes())
    assert seen[at - 1] <= final
    assert len(final) > len(seen[at - 1])

