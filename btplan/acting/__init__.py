"""The acting layer: Algorithm 1 run against a world, offline (planning) and online (acting).

`loop` ticks the tree and grows it where it fails (its parts are listed in `state`);
`offline` plans a tree from the initial state; `online` acts with external agents and
records each tick; `records` holds the per-tick records and the run summary;
`live_view` draws them in a terminal; `ahead`, `watch` and `scope` are options of the
online loop (look ahead along an action's preconditions; expand a condition ahead of the
running action when an agent breaks it; skip a moved subtree while what it was moved
for holds).
The names below are imported on first use (PEP 562): planning needs neither the
online loop nor its agents.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.acting.offline import PlanResult, PlanStats
    from btplan.acting.clock import FakeClock
    from btplan.acting.config import ActingConfig
    from btplan.acting.loop import BlendedLoop, Expansion, TickReport
    from btplan.acting.offline import load, plan
    from btplan.acting.online import ACTING_OPTIONS, RunOutcome, run, task_models

_HOMES = {"ActingConfig": "config", "FakeClock": "clock", "BlendedLoop": "loop",
          "Expansion": "loop", "TickReport": "loop",
          "PlanResult": "offline", "PlanStats": "offline", "load": "offline", "plan": "offline",
          "ACTING_OPTIONS": "online", "RunOutcome": "online", "run": "online",
          "task_models": "online"}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'btplan.acting' has no attribute {name!r}")
    return getattr(importlib.import_module(f"btplan.acting.{home}"), name)


__all__ = [
    "ACTING_OPTIONS",
    "ActingConfig",
    "FakeClock",
    "BlendedLoop",
    "Expansion",
    "PlanResult",
    "PlanStats",
    "RunOutcome",
    "TickReport",
    "load",
    "plan",
    "run",
    "task_models",
]
