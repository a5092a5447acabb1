"""Run records and the JSON-lines trace: complete, consistent, and the same for the same seed."""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path

from btplan.acting.offline import load
from btplan.acting.online import run
from btplan.acting.records import TickRecord, records_to_jsonl

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
TASK = load(str(DOMAINS / "pick_place.bt"))
NOISY = ["undo@p=0.1", "help@p=0.05", "fail:MoveTo@p=0.1"]


def test_the_same_seed_gives_the_same_trace_byte_for_byte() -> None:
    first = records_to_jsonl(run(TASK, disturb=NOISY, seed=3, max_ticks=200).records)
    again = records_to_jsonl(run(TASK, disturb=NOISY, seed=3, max_ticks=200).records)
    other = records_to_jsonl(run(TASK, disturb=NOISY, seed=4, max_ticks=200).records)
    assert first == again
    assert first != other


def test_fact_changes_replay_the_state_from_the_initial_one() -> None:
    """Applying each tick's added/removed facts to the initial state gives the final state."""
    result = run(TASK, disturb=NOISY, seed=1, max_ticks=200)
    state = {str(a) for a in TASK.initial_state}
    for record in result.records:
        assert not set(record.added) & state
        assert set(record.removed) <= state
        state = (state - set(record.removed)) | set(record.added)
    assert state == {str(a) for a in result.world.facts()}


def test_each_line_names_the_nodes_reached_and_their_statuses() -> None:
    result = run(TASK)
    lines = [json.loads(line) for line in records_to_jsonl(result.records).splitlines()]
    assert len(lines) == result.ticks
    last = lines[-1]
    assert last["status"] == "SUCCESS"
    assert last["nodes"][0] == {"id": "n0", "kind": "Fallback", "name": "", "status": "SUCCESS"}
    assert last["nodes"][1]["name"] == "on(cube, goal)"
    assert last["finished"] == ["Place(cube, goal)"]
    assert sum(len(line["expansions"]) for line in lines) == len(result.summary().expansions)
    executed = [a for line in lines for a in line["finished"]]
    assert executed == [str(a) for a in result.executed]


def test_every_node_a_tick_reached_has_its_status_in_the_view_from_the_first_tick() -> None:
    """The default loop plans the whole tree before its first action, within tick 1: the
    statuses the view gets must be those of that tree, not of the goal-only tree before."""
    seen: list[tuple[int, int, int]] = []

    def view(root: object, reached: Mapping[int, object], record: TickRecord) -> None:
        seen.append((record.tick, len(reached), len(record.nodes)))

    result = run(TASK, view=view)
    assert result.reached
    assert seen[0][2] > 1
    assert [(tick, count) for tick, count, _ in seen] == [(tick, nodes) for tick, _, nodes in seen]
