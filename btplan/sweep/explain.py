"""Why a failed run failed: no way to the goal within the budget, or the method's own doing.

A run fails when the goal is not reached within the tick budget. Rerunning its seed
with `replan-unlimited` (replanning from scratch whenever the rest of its plan breaks,
with no limit on calls per tick) tells the two apart: when that fails too, the disturbed
world left no way to the goal in time, whatever the executor; when it reaches the goal,
the failure is the method's own, and the run's `reason` says how it ended. Reruns are
needed only for failed runs, and never twice for one (rate, seed).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from btplan.sweep.runs import Row

REFERENCE = "replan-unlimited"

NO_WAY = "no way in budget"
"""Replanning without limit fails on the same seed too."""

OWN = "own"
"""Replanning without limit reaches the goal on the same seed: a weakness or a defect."""

UNCHECKED = "not checked"
"""No reference run (another simulator, a non-STRIPS task, pyperplan missing, a crash)."""

CAUSES = (NO_WAY, OWN, UNCHECKED)

Key = tuple[float, int]


def failed(row: Row) -> bool:
    """Ended without reaching the goal (a crash is an error, not a failure)."""
    return not row["success"] and not row["error"]


def references(rows: Iterable[Row]) -> dict[Key, Row]:
    """The reference runs among `rows`, by (rate, seed)."""
    return {(float(r["rate"]), int(r["seed"])): r for r in rows if r["method"] == REFERENCE}


def needed(rows: Sequence[Row]) -> list[tuple[str, float, int]]:
    """The reference runs still to do: one per (rate, seed) with a failure and none yet."""
    have = references(rows)
    keys = sorted({(float(r["rate"]), int(r["seed"])) for r in rows if failed(r)} - set(have))
    return [(REFERENCE, rate, seed) for rate, seed in keys]


def label(rows: Sequence[Row], reference: Mapping[Key, Row]) -> None:
    """Fill `cause` in every failed row from the reference run of its seed."""
    for row in rows:
        if not failed(row):
            row["cause"] = ""
            continue
        ref = reference.get((float(row["rate"]), int(row["seed"])))
        if row["method"] == REFERENCE:
            row["cause"] = NO_WAY
        elif ref is None or ref["error"]:
            row["cause"] = UNCHECKED
        else:
            row["cause"] = OWN if ref["success"] else NO_WAY


def tally(rows: Sequence[Row]) -> list[tuple[str, str, float, int, dict[str, int]]]:
    """Failed runs per (scenario, method, rate), counted by cause."""
    counts: dict[tuple[str, str, float], dict[str, int]] = {}
    for row in rows:
        if failed(row):
            key = (str(row["scenario"]), str(row["method"]), float(row["rate"]))
            bucket = counts.setdefault(key, dict.fromkeys(CAUSES, 0))
            cause = row.get("cause") or UNCHECKED
            bucket[cause] = bucket.get(cause, 0) + 1
    return [(s, m, r, sum(c.values()), c) for (s, m, r), c in sorted(counts.items())]


def markdown(rows: Sequence[Row]) -> str:
    """The failed runs by cause, as a table (empty when every run reached the goal)."""
    lines = tally(rows)
    if not lines:
        return ""
    out = ["| scenario | method | rate | failed | " + " | ".join(CAUSES) + " |",
           "|---|---|---:|---:|" + "---:|" * len(CAUSES)]
    for scenario, method, rate, total, counts in lines:
        out.append(f"| {scenario} | {method} | {rate:g} | {total} | "
                   + " | ".join(str(counts[c]) for c in CAUSES) + " |")
    return "\n".join(out) + "\n"
