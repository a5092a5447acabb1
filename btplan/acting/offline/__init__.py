"""Offline planning: Algorithm 1 run against the symbolic world until the tree needs no
expansion from the initial state (`plan`), with its strategies, retries, the whole-goal
search and plan improvement. `planning` is the front door; one attempt's rounds are in
`attempt`, the shortened plan put ahead of the tree in `improved`, the whole-goal search
turns in `whole_goal`. `run` (acting online) is re-exported for the library's callers.
"""

from __future__ import annotations

from btplan.acting.offline.attempt import PlanResult, PlanStats
from btplan.acting.offline.planning import load, plan

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.acting.online import RunOutcome, run


def __getattr__(name: str) -> Any:
    """`run` and `RunOutcome` from btplan.acting.online, on first use (acting pulls in
    the worlds' agents, which planning does not need)."""
    if name in ("run", "RunOutcome"):
        from btplan.acting import online

        return getattr(online, name)
    raise AttributeError(f"module 'btplan.acting.offline' has no attribute {name!r}")


__all__ = ["PlanResult", "PlanStats", "RunOutcome", "load", "plan", "run"]
