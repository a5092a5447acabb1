"""The acting layer: Algorithm 1 run against a world, offline (planning) and online (acting).

`loop` ticks the tree and grows it where it fails; `offline` plans a tree from the
initial state; `online` acts with external agents and records each tick; `records`
holds the per-tick records and the run summary; `live_view` draws them in a terminal.
"""

from btplan.acting.loop import BlendedLoop, Expansion, TickReport
from btplan.acting.offline import PlanResult, PlanStats, load, plan
from btplan.acting.online import ACTING_OPTIONS, RunOutcome, run, task_models

__all__ = [
    "ACTING_OPTIONS",
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
