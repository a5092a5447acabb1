"""Large traces made up for the browser view's tests and bench/browser_view.py."""

from __future__ import annotations

import json


def big_trace(nodes: int) -> list[str]:
    """A trace of three ticks over a tree of `nodes` nodes, grown breadth first: every
    control node has a condition, two Sequences and an action under it."""
    rows: list[list[object]] = [[1, 0, "Fallback", ""]]
    frontier = [1]
    while len(rows) < nodes:
        parent = frontier.pop(0)
        for kind in ("Condition", "Sequence", "Sequence", "Action"):
            if len(rows) >= nodes:
                break
            uid = len(rows) + 1
            rows.append([uid, parent, kind, f"{kind.lower()}_{uid}(x{uid % 7}, y{uid % 11})"
                         if kind != "Sequence" else ""])
            if kind == "Sequence":
                frontier.append(uid)
    running = [r[0] for r in rows if r[2] == "Action"][-1]
    lines = []
    for tick in (1, 2, 3):
        line: dict[str, object] = {
            "tick": tick, "status": "RUNNING", "nodes": [], "started": [], "halted": [],
            "finished": [], "failed": [], "disturbances": [], "expansions": [],
            "facts": {"added": [f"f{tick}"], "removed": []},
            "statuses": [[1, "RUNNING"], [running, "RUNNING"]]}
        if tick == 1:
            line["tree"], line["facts_at_start"] = rows, ["start"]
        lines.append(json.dumps(line))
    return lines
