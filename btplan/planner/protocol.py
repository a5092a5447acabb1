"""What the planner needs from a world beyond ticking: the state and refinement.

Structural: a world satisfies it without importing the planner.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.bt import World
from btplan.grounding import Refiner
from btplan.model import ActionTemplate, Atom, Parameter

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

__all__ = ["PlanningWorld", "Refiner"]


class PlanningWorld(World, Protocol):
    """A world the acting loop can plan against."""

    def facts(self) -> frozenset[Atom]:
        """The current state as ground atoms."""
        ...

    def refine(
        self, template: ActionTemplate, binding: Mapping[str, str], parameter: Parameter
    ) -> list[str]:
        """Values for `parameter` under `binding`, best first, deterministic."""
        ...
