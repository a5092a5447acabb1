"""`btplan view`'s input checks, and the lines a live view keeps."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from btplan.cli import app
from btplan.monitor.browser import TraceLines

runner = CliRunner()


def tick(number: int, added: list[str], removed: list[str], **more: object) -> str:
    line = {"tick": number, "status": "RUNNING", "facts": {"added": added, "removed": removed},
            "statuses": [], **more}
    return json.dumps(line)


def test_a_file_that_is_not_a_trace_is_bad_input_at_its_line(tmp_path: Path) -> None:
    trace = tmp_path / "t.jsonl"
    trace.write_text(tick(1, [], [], tree=[[1, 0, "Action", "A"]]) + "\n{oops\n")
    result = runner.invoke(app, ["view", str(trace)])
    assert result.exit_code == 2 and f"{trace}:2:" in result.output
    assert "not a JSON line" in result.output


def test_a_trace_without_the_tree_is_refused_with_a_hint(tmp_path: Path) -> None:
    trace = tmp_path / "old.jsonl"
    trace.write_text(tick(1, [], []) + "\n")
    result = runner.invoke(app, ["view", str(trace)])
    assert result.exit_code == 2 and "does not hold the tree" in result.output
    missing = runner.invoke(app, ["view", str(tmp_path / "none.jsonl")])
    assert missing.exit_code == 2 and "no such file" in missing.output


def test_a_live_view_folds_the_ticks_it_drops_into_a_base_line() -> None:
    lines = TraceLines(keep=2)
    lines.append(tick(1, ["b"], [], tree=[[1, 0, "Action", "A"]], facts_at_start=["a"]))
    lines.append(tick(2, ["c"], ["a"]))
    lines.append(tick(3, [], ["b"], tree=[[1, 0, "Fallback", ""], [2, 1, "Action", "A"]]))
    lines.append(tick(4, ["d"], []))
    kept, total = lines.since(0)
    assert total == 4 and len(kept) == 3
    base = json.loads(kept[0])
    assert base["base"] and base["tick"] == 2
    assert base["tree"] == [[1, 0, "Action", "A"]]  # the tree ticks 3 and 4 start from
    assert base["facts_at_start"] == ["b", "c"]  # the facts after tick 2
    assert [json.loads(k)["tick"] for k in kept[1:]] == [3, 4]
    assert lines.since(3) == ([kept[2]], 4) and lines.since(4) == ([], 4)
