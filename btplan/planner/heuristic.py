"""A relaxed-reachability estimate (h_add) over the grounded domain.

Preconditions on refined parameters are dropped: the backend will supply a value (a
trajectory, a pose) that meets them when the action is chosen.

The paper orders achievers arbitrarily ("we do not investigate which action is the
optimal one"). On classic domains that first match is often a poor choice, so btplan
ranks achievers by the additive cost of reaching their preconditions when delete
effects are ignored (Bonet and Geffner's h_add), and drops achievers whose
preconditions cannot be reached at all.
"""

from __future__ import annotations

import heapq
from collections import deque
import math
from collections.abc import Callable, Iterable

from btplan.model import ActionTemplate, Atom, GroundAction, Task, ground_literal, instantiate
from btplan.planner.grounding import PLACEHOLDER, Objects, bindings


COST_CACHE = 8
"""States whose h_add costs are kept (planning goes back and forth between a few)."""


class RelaxedModel:
    """Every grounding of the domain that static facts allow, indexed for h_add."""

    def __init__(
        self,
        task: Task,
        limit: int = 200_000,
        objects: Objects | None = None,
        ground: Callable[[ActionTemplate, tuple[str, ...]], GroundAction] = instantiate,
    ) -> None:
        self.actions: list[GroundAction] = []
        table = objects or Objects(task)
        for template in task.domain.actions:
            for binding in bindings(
                task, template, {}, task.initial_state, None, limit, table, optimistic=True
            ):
                args = tuple(binding[p.name] for p in template.parameters)
                action = ground(template, args)
                if action.cost < math.inf:  # an undefined cost makes it inapplicable
                    self.actions.append(_optimistic(template, binding, action))
        self._pre: list[tuple[Atom, ...]] = [
            tuple(p.atom for p in a.preconditions if p.positive) for a in self.actions
        ]
        self._by_pre: dict[Atom, list[int]] = {}
        for i, pre in enumerate(self._pre):
            for atom in set(pre):
                self._by_pre.setdefault(atom, []).append(i)
        self._waiting = [len(set(pre)) for pre in self._pre]
        self._free = [i for i, n in enumerate(self._waiting) if n == 0]
        self._producers: dict[Atom, list[GroundAction]] | None = None
        self._cache: dict[frozenset[Atom], dict[Atom, float]] = {}

    def costs(self, state: frozenset[Atom]) -> dict[Atom, float]:
        """h_add cost of every reachable atom from `state` (generalised Dijkstra)."""
        cached = self._cache.get(state)
        if cached is not None:
            return cached
        cost: dict[Atom, float] = {a: 0.0 for a in state}
        waiting = list(self._waiting)
        queue: list[tuple[float, Atom]] = [(0.0, a) for a in sorted(state)]
        heapq.heapify(queue)
        done: set[Atom] = set()
        fired = [False] * len(self.actions)
        for i, n in enumerate(waiting):
            if n == 0:
                fired[i] = True
                self._relax(i, 0.0, cost, queue)
        while queue:
            value, atom = heapq.heappop(queue)
            if atom in done or value > cost.get(atom, math.inf):
                continue
            done.add(atom)
            for i in self._by_pre.get(atom, ()):
                waiting[i] -= 1
                if waiting[i] == 0 and not fired[i]:
                    fired[i] = True
                    total = sum(cost[p] for p in set(self._pre[i]))
                    self._relax(i, total, cost, queue)
        if len(self._cache) >= COST_CACHE:
            del self._cache[next(iter(self._cache))]
        self._cache[state] = cost
        return cost

    def _relax(
        self, i: int, pre_cost: float, cost: dict[Atom, float], queue: list[tuple[float, Atom]]
    ) -> None:
        value = pre_cost + self.actions[i].cost
        for atom in self.actions[i].add:
            if value < cost.get(atom, math.inf):
                cost[atom] = value
                heapq.heappush(queue, (value, atom))

    def reachable(self, state: frozenset[Atom], targets: Iterable[Atom]) -> bool:
        """Whether every target can be reached from `state` ignoring deletes.

        Plain relaxed reachability, stopping as soon as the last target is reached:
        cheaper than `costs` when only yes or no matters.
        """
        missing = {t for t in targets if t not in state}
        if not missing:
            return True
        waiting = list(self._waiting)
        reached = set(state)
        frontier = deque(state)
        for i in self._free:
            for atom in self.actions[i].add:
                if atom not in reached:
                    reached.add(atom)
                    frontier.append(atom)
        while frontier:
            atom = frontier.popleft()
            missing.discard(atom)
            if not missing:
                return True
            for i in self._by_pre.get(atom, ()):
                waiting[i] -= 1
                if waiting[i] == 0:
                    for added in self.actions[i].add:
                        if added not in reached:
                            reached.add(added)
                            frontier.append(added)
        return False

    def producers(self, atom: Atom) -> list[GroundAction]:
        """The grounded actions that add `atom`."""
        if self._producers is None:
            self._producers = {}
            for action in self.actions:
                for added in action.add:
                    self._producers.setdefault(added, []).append(action)
        return self._producers.get(atom, [])

    def estimate(self, state: frozenset[Atom], atoms: Iterable[Atom]) -> float:
        """Sum of h_add costs; infinite when some atom is unreachable."""
        cost = self.costs(state)
        return sum(cost.get(a, math.inf) for a in atoms)


def _optimistic(
    template: ActionTemplate, binding: dict[str, str], action: GroundAction
) -> GroundAction:
    """Assume the backend supplies refined values that satisfy their preconditions.

    A precondition on a refined parameter (free(t) of a trajectory) is the backend's
    to meet, so it is dropped; effects on the placeholder say nothing and go too.
    """
    refined = {p.name for p in template.parameters if p.refined}
    if not refined:
        return action
    dropped = {
        ground_literal(lit, binding).atom
        for lit in template.preconditions if refined & set(lit.args)
    }
    return action.model_copy(update={
        "preconditions": tuple(
            p for p in action.preconditions
            if p.atom not in dropped and PLACEHOLDER not in p.atom.args),
        "add": tuple(a for a in action.add if PLACEHOLDER not in a.args),
        "delete": tuple(a for a in action.delete if PLACEHOLDER not in a.args),
    })
