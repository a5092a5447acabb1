"""The last-resort search in a world that supplies values the task does not declare.

btplan.acting.departures.search plans a stuck condition over the task's groundings. In the
simulator those have no trajectory and no put-aside pose, so no MoveTo and no Place to
a pose at all: a condition stuck there stayed stuck, and the run ended where the tree
had chosen an order it could not complete. Here the search plans with the actions
grounded with what the world refines now, as a task-and-motion planner grounds its
motions when it plans (the baselines' grounding, btplan.acting.refined), and with
their wildcard deletes (`not near(_)`) written out (btplan.classical.spell_out).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from btplan.acting.refined import RefinedGrounding, asks_world
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.classical import MAX_STATES, SubgoalSearch, spell_out


class RefinedSearch:
    """SubgoalSearch over the groundings the world refines, grounded anew for each state.

    `observe` grounds and measures first (the paths of every value given, as the
    baselines do before they plan); `search` then plans from the state it returned.
    """

    def __init__(self, task: Task, world: Any) -> None:
        self.grounding = RefinedGrounding(task, world)
        self.world = world
        self._actions: list[GroundAction] = []

    def observe(self, facts: frozenset[Atom]) -> frozenset[Atom]:
        """The state to plan from: the world's facts with every refined path measured."""
        self._actions = self.grounding.actions(facts)
        return self.grounding.observe(self.world)

    def search(self, start: frozenset[Atom], goal: Sequence[GroundLiteral],
               max_states: int = MAX_STATES, deadline: float | None = None,
               keep: Sequence[GroundLiteral] = ()) -> list[GroundAction] | None:
        """A plan from `start` to `goal` with the actions grounded by `observe`; its steps
        are those actions, wildcard deletes and all, as the tree runs them."""
        named = [*start, *(g.atom for g in goal), *(n for a in self._actions for n in a.needs)]
        engine = SubgoalSearch(spell_out(self._actions, named))
        steps = engine.search(start, goal, max_states, deadline, keep)
        if steps is None:
            return None
        original = {a.key: a for a in self._actions}
        return [original[s.key] for s in steps]


def refines_for(task: Task, world: Any) -> bool:
    """Whether the last resort must ground with the world's values: it refines, and the
    task declares no object of a refined parameter's type (refined.asks_world)."""
    return callable(getattr(world, "refine", None)) and asks_world(task)
