"""A classical planner over the grounded model: what backchaining asks of search.

Reachability and the relaxed model (`reach`, `heuristic`: h_add, h_FF), h^2 mutexes and
lifted invariants (`mutex`, `invariants`), greedy best-first search over states packed
in ints (`search`, `packed`), a lower bound on any plan (`bound`: LM-cut), and a shorter
plan after planning (`improvement`, `neighbourhood`). None of it knows of trees: the PA-BT
steps in btplan.planner use these names, never the modules behind them, and this
package never imports btplan.planner. The names are imported on first use (PEP 562), so
a planning call that needs no search does not load it.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.classical.bound import fewest_steps, no_better_plan
    from btplan.classical.heuristic import RelaxedModel
    from btplan.classical.improvement import Improvement, improve
    from btplan.classical.invariants import MutexGroups
    from btplan.classical.mutex import Mutexes
    from btplan.classical.neighbourhood import Limits, PlanSpace
    from btplan.classical.packed import PackedActions
    from btplan.classical.search import MAX_STATES, Portfolio, SearchRun, SubgoalSearch, spell_out

_HOMES = {
    "fewest_steps": "bound", "no_better_plan": "bound",
    "RelaxedModel": "heuristic",
    "Improvement": "improvement", "improve": "improvement",
    "MutexGroups": "invariants",
    "Mutexes": "mutex",
    "Limits": "neighbourhood", "PlanSpace": "neighbourhood",
    "PackedActions": "packed",
    "MAX_STATES": "search", "Portfolio": "search", "SearchRun": "search",
    "SubgoalSearch": "search", "spell_out": "search",
}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'btplan.classical' has no attribute {name!r}")
    return getattr(importlib.import_module(f"btplan.classical.{home}"), name)


__all__ = [
    "Improvement",
    "Limits",
    "MAX_STATES",
    "MutexGroups",
    "Mutexes",
    "PackedActions",
    "PlanSpace",
    "Portfolio",
    "RelaxedModel",
    "SearchRun",
    "SubgoalSearch",
    "fewest_steps",
    "improve",
    "no_better_plan",
    "spell_out",
]
