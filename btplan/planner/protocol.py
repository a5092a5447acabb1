"""What the planner needs from a world beyond ticking: the state and refinement.

Structural: a world satisfies it without importing the planner.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from btplan.bt import World
from btplan.model import ActionTemplate, Atom, Parameter

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

Refiner = Callable[[ActionTemplate, Mapping[str, str], Parameter], list[str]]
"""Supplies values for a `refined` parameter, best first (the paper's RefineActions)."""


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
