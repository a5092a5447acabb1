"""btplan: planning domains to reactive Behavior Trees."""

__version__ = "0.1.0"

from btplan.acting import PlanResult, RunOutcome, load, plan, run

__all__ = ["PlanResult", "RunOutcome", "__version__", "load", "plan", "run"]
