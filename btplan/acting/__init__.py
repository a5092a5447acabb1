"""The acting layer: Algorithm 1 run against a world, offline (planning) and online (acting).

- `loop`: Algorithm 1 (tick, GetConditionToExpand, ExpandTree, IncreasePriority), with
  its own parts `choice`, `early`, `progress`, `diagnosis`, and `skills` (the robot as
  the tree sees it: one run per grounded action, the logs, safe halting);
- `hooks` and `departures/`: every departure from the paper, an object behind a hook;
- `config`: `ActingConfig` and its presets (`paper`, `algorithm1`, `default`, `simulator`);
- `online`: a run (agents, a fixed rate on a `clock`, `keep`, every way out halted),
  recorded tick by tick by `recorder` into `records`, drawn by `live_view`;
- `offline/`: planning a tree from the initial state (`plan`), and `offline_turns`,
  which plans offline from the state of now before the first action and when the loop
  is stuck.
The benchmark's baselines live apart, in btplan.baselines. The names below are imported on first use (PEP 562): planning needs neither the
online loop nor its agents.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.acting.clock import FakeClock
    from btplan.acting.config import ActingConfig
    from btplan.acting.loop import BlendedLoop, Expansion, TickReport
    from btplan.acting.offline import PlanResult, PlanStats, load, plan
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
