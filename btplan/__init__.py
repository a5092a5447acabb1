"""btplan: planning domains to reactive Behavior Trees."""

__version__ = "0.1.0"

from btplan.api import PlanResult, load, plan

__all__ = ["PlanResult", "__version__", "load", "plan"]
