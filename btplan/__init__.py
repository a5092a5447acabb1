"""btplan: planning domains to reactive Behavior Trees.

The names below come from the acting layer, which pulls in the planner, the trees and
the worlds; they are imported on first use (PEP 562) so that `import btplan` (and every
`btplan ...` command, which imports this package first) starts without them.
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any


__version__ = "0.1.0"

if TYPE_CHECKING:
    from btplan.acting import PlanResult, RunOutcome, load, plan, run

_FROM_ACTING = ("PlanResult", "RunOutcome", "load", "plan", "run")


def __getattr__(name: str) -> Any:
    if name in _FROM_ACTING:
        from btplan import acting

        return getattr(acting, name)
    raise AttributeError(f"module 'btplan' has no attribute {name!r}")


__all__ = ["PlanResult", "RunOutcome", "__version__", "load", "plan", "run"]
