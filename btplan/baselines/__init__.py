"""The methods btplan is measured against in `btplan sweep`: replanning and plan repair.

They act in the same worlds as the blended loop, with a classical planner instead of a
growing tree (`methods`); the STRIPS grounding they plan on is btplan.acting.strips (and
btplan.acting.refined for worlds that refine values), which the loop's last-resort
search shares.
"""

from __future__ import annotations

from btplan.baselines.methods import BASELINES, BaselineOutcome, run_baseline

__all__ = ["BASELINES", "BaselineOutcome", "run_baseline"]
