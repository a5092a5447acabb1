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
import math
from collections.abc import Callable, Iterable
from itertools import compress

from btplan.model import ActionTemplate, Atom, GroundAction, Task, ground_literal, instantiate
from btplan.grounding import PLACEHOLDER, Objects, bindings
from btplan.classical.reach import reachable_bindings
from btplan.collector import building

COST_CACHE = 8
"""States whose h_add costs are kept (planning goes back and forth between a few)."""


class RelaxedModel:
    """The domain's groundings that can run in some relaxed state reached from the
    initial state (every one the static facts allow, where a world refines parameters),
    indexed for h_add."""

    def __init__(
        self,
        task: Task,
        limit: int = 200_000,
        objects: Objects | None = None,
        ground: Callable[[ActionTemplate, tuple[str, ...]], GroundAction] = instantiate,
        reach: bool = True,
    ) -> None:
        """`reach`: only the groundings relaxed-reachable from the initial state
        (btplan/classical/reach.py); off, every grounding the static facts allow."""
        self.actions: list[GroundAction] = []
        self.complete = True
        """Whether no action template had more groundings than `limit` (then the model
        holds every action a plan from the initial state can take)."""
        table = objects or Objects(task)
        with building():
            self._ground(task, table, limit, reach, ground)

    def _ground(self, task: Task, table: Objects, limit: int, reach: bool,
                ground: Callable[[ActionTemplate, tuple[str, ...]], GroundAction]) -> None:
        found, self.complete = _groundings(task, table, limit, reach)
        for template, args in found:
            action = ground(template, args)
            if action.cost < math.inf:  # an undefined cost makes it inapplicable
                binding = {p.name: a for p, a in zip(template.parameters, args)}
                self.actions.append(_optimistic(template, binding, action))
        self._pre: list[tuple[Atom, ...]] = [a.needs for a in self.actions]
        self._by_pre: dict[Atom, list[int]] = {}
        for i, pre in enumerate(self._pre):
            for atom in set(pre):
                self._by_pre.setdefault(atom, []).append(i)
        self._waiting = [len(set(pre)) for pre in self._pre]
        self._free = [i for i, n in enumerate(self._waiting) if n == 0]
        self._producers: dict[Atom, list[GroundAction]] | None = None
        self._producer_needs: dict[Atom, list[tuple[Atom, ...]]] = {}
        self._cache: dict[frozenset[Atom], dict[Atom, float]] = {}
        self._encode()

    def _encode(self) -> None:
        """Atoms as integers and actions as lists of them, for `costs`: h_add runs once
        per state the tree is ticked in, and hashing and comparing atoms was most of it."""
        ids: dict[Atom, int] = {}
        for action in self.actions:
            for atom in (*action.needs, *action.add):
                ids.setdefault(atom, len(ids))
        self._ids = ids
        self._atoms = list(ids)
        self._add_ids = [tuple(dict.fromkeys(ids[a] for a in act.add)) for act in self.actions]
        self._action_cost = [float(act.cost) for act in self.actions]
        self._uniform = len(set(self._action_cost)) <= 1
        self._adders: dict[int, list[int]] | None = None
        self._whole = all(c.is_integer() and c >= 0 for c in self._action_cost)
        self._visits: int | None = None
        self._integral = all(c.is_integer() and 0 <= c < 2 ** 40 for c in self._action_cost)
        self._pre_ids: list[tuple[int, ...]] | None = None
        self._by_pre_id: list[list[int]] = [[] for _ in ids]
        for i, pre in enumerate(self._pre):
            for atom in set(pre):
                self._by_pre_id[ids[atom]].append(i)

    def numbered(self) -> tuple[dict[Atom, int], list[tuple[int, ...]], list[tuple[int, ...]]]:
        """The atom numbers of `costs`, and each action's positive preconditions and adds
        as those numbers (for other estimates over the same model: bound.py)."""
        ids = self._ids
        if self._pre_ids is None:  # once: a model is kept for later planning calls
            self._pre_ids = [tuple([ids[a] for a in pre]) for pre in self._pre]
        return ids, self._pre_ids, self._add_ids

    def adders(self) -> dict[int, list[int]]:
        """The numbers of the actions adding each atom, by the atom's number (bound.py:
        its relevance sweep starts from the goals, once per planning call; the model
        outlives the call, so the index is made once)."""
        if self._adders is None:
            self._adders = {}
            for i, added in enumerate(self._add_ids):
                for atom in added:
                    self._adders.setdefault(atom, []).append(i)
        return self._adders

    def uniform(self) -> bool:
        """Whether every action costs the same."""
        return self._uniform

    def whole_costs(self) -> bool:
        """Whether every action's cost is a whole, non-negative number (bound.py's sums
        are exact then)."""
        return self._whole

    def precondition_visits(self) -> int:
        """The preconditions of all actions, an action without any counted once: what a
        round of LM-cut over the whole model visits at most (bound.py's work limit)."""
        if self._visits is None:
            self._visits = sum(max(1, len(set(pre))) for pre in self._pre)
        return self._visits

    def action_costs(self) -> list[float]:
        """Each action's cost, in the order of `actions` (and of `numbered`)."""
        return self._action_cost

    def costs(self, state: frozenset[Atom]) -> dict[Atom, float]:
        """h_add cost of every reachable atom from `state` (generalised Dijkstra)."""
        cached = self._cache.get(state)
        if cached is not None:
            return cached
        if self._integral:
            cost = self._sweep_levels(state)
        else:
            cost = self._sweep_heap(state)
        # {a: 0.0 for a in state}, then every atom of finite cost, iterated in C
        found = dict.fromkeys(state, 0.0)
        found.update(compress(zip(self._atoms, cost), map(math.inf.__gt__, cost)))
        if len(self._cache) >= COST_CACHE:
            del self._cache[next(iter(self._cache))]
        self._cache[state] = found
        return found

    def _start(self, state: frozenset[Atom]) -> list[float]:
        """Costs with the state's atoms at 0 and everything else unknown."""
        ids = self._ids
        cost = [math.inf] * len(ids)
        for atom in state:
            at = ids.get(atom)
            if at is not None:
                cost[at] = 0.0
        return cost

    def _sweep_heap(self, state: frozenset[Atom]) -> list[float]:
        """Dijkstra with a heap of atoms: right for any non-negative action costs."""
        by_pre, adds, action_cost = self._by_pre_id, self._add_ids, self._action_cost
        cost = self._start(state)
        queue = [(0.0, at) for at, value in enumerate(cost) if value == 0.0]
        heapq.heapify(queue)
        waiting = list(self._waiting)
        summed = [0.0] * len(waiting)  # the costs of an action's preconditions so far
        push, pop = heapq.heappush, heapq.heappop
        for i in self._free:
            for at in adds[i]:
                if action_cost[i] < cost[at]:
                    cost[at] = action_cost[i]
                    push(queue, (action_cost[i], at))
        done = [False] * len(cost)
        while queue:
            value, at = pop(queue)
            if done[at] or value > cost[at]:
                continue
            done[at] = True
            for i in by_pre[at]:
                summed[i] += value
                waiting[i] -= 1
                if waiting[i] == 0:
                    total = summed[i] + action_cost[i]
                    for added in adds[i]:
                        if total < cost[added]:
                            cost[added] = total
                            push(queue, (total, added))
        return cost

    def _sweep_levels(self, state: frozenset[Atom]) -> list[float]:
        """Dijkstra with one bucket per cost value, for whole-number action costs.

        Sums of whole numbers are exact in any order, so the values are those of
        `_sweep_heap`; popping a heap entry per atom was a third of the time on large
        problems, and only the few distinct values need the heap here. An atom enters a
        bucket only when its cost falls to that bucket's value, so the one whose cost
        is still that value is in it once: reading it settles it, with no mark kept.
        An action fires when its last precondition is read (`waiting` falls no lower
        than 1: nothing reads it after that).
        """
        by_pre, adds, action_cost = self._by_pre_id, self._add_ids, self._action_cost
        ids = self._ids
        cost = [math.inf] * len(ids)
        start: list[int] = []
        for atom in state:
            at = ids.get(atom)
            if at is not None:
                cost[at] = 0.0
                start.append(at)
        buckets: dict[float, list[int]] = {0.0: start}
        levels = [0.0]
        for i in self._free:
            for at in adds[i]:
                value = action_cost[i]
                if value < cost[at]:
                    cost[at] = value
                    if value in buckets:
                        buckets[value].append(at)
                    else:
                        buckets[value] = [at]
                        heapq.heappush(levels, value)
        waiting = list(self._waiting)
        summed = [0.0] * len(waiting)
        while levels:
            value = heapq.heappop(levels)
            bucket = buckets[value]
            for at in bucket:  # grows while read when an action costs nothing
                if value > cost[at]:
                    continue  # settled at a lower value already
                for i in by_pre[at]:
                    left = waiting[i]
                    if left > 1:
                        waiting[i] = left - 1
                        summed[i] += value
                        continue
                    total = summed[i] + value + action_cost[i]
                    for added in adds[i]:
                        if total < cost[added]:
                            cost[added] = total
                            if total in buckets:
                                buckets[total].append(added)
                            else:
                                buckets[total] = [added]
                                heapq.heappush(levels, total)
            del buckets[value]
        return cost

    def reachable(self, state: frozenset[Atom], targets: Iterable[Atom]) -> bool:
        """Whether every target can be reached from `state` ignoring deletes.

        Plain relaxed reachability, stopping as soon as the last target is reached:
        cheaper than `costs` when only yes or no matters.
        """
        targets = list(targets)
        return len(self.reachable_avoiding(state, set(), targets)) == len(set(targets))

    def reachable_avoiding(self, state: frozenset[Atom], avoided: set[Atom],
                           targets: Iterable[Atom]) -> set[Atom]:
        """The targets reachable from `state`, ignoring deletes, with no action that needs
        an avoided atom (and the avoided atoms false, even where `state` has them).

        A target only reachable through a state where an avoided atom holds needs that
        atom first: an achiever of g that needs it cannot help a fallback pursuing g.
        """
        targets = [t for t in targets if t not in avoided]
        found = {t for t in targets if t in state}
        ids = self._ids
        wanted = {ids[t] for t in targets if t not in state and t in ids}
        if not wanted:
            return found
        adds, by_pre, atoms = self._add_ids, self._by_pre_id, self._atoms
        reached = [False] * len(ids)
        blocked: set[int] = set()
        for atom in avoided:
            at = ids.get(atom)
            if at is not None:
                reached[at] = True  # never reached, never fires what needs it
                blocked.update(self._by_pre.get(atom, ()))
        frontier: list[int] = []  # breadth first: what is near the state comes first
        for atom in state:
            at = ids.get(atom)
            if at is not None and not reached[at]:
                reached[at] = True
                frontier.append(at)
        waiting = list(self._waiting)
        fired = [i for i in self._free if i not in blocked]
        head = 0
        while True:
            for i in fired:
                for at in adds[i]:
                    if not reached[at]:
                        reached[at] = True
                        frontier.append(at)
                        if at in wanted:
                            wanted.discard(at)
                            found.add(atoms[at])
                            if not wanted:
                                return found
            if head == len(frontier):
                return found
            fired = []
            for i in by_pre[frontier[head]]:
                waiting[i] -= 1
                if waiting[i] == 0 and i not in blocked:
                    fired.append(i)
            head += 1

    def producers(self, atom: Atom) -> list[GroundAction]:
        """The grounded actions that add `atom`."""
        if self._producers is None:
            self._producers = {}
            for action in self.actions:
                for added in action.add:
                    self._producers.setdefault(added, []).append(action)
        return self._producers.get(atom, [])

    def producer_needs(self, atom: Atom) -> list[tuple[Atom, ...]]:
        """The positive preconditions of each of `producers(atom)`, in that order; taken
        apart once per atom (the look-ahead asks of every achiever it weighs)."""
        needs = self._producer_needs.get(atom)
        if needs is None:
            needs = self._producer_needs[atom] = [
                action.needs for action in self.producers(atom)]
        return needs

    def estimate(self, state: frozenset[Atom], atoms: Iterable[Atom]) -> float:
        """Sum of h_add costs; infinite when some atom is unreachable."""
        cost = self.costs(state)
        return sum(cost.get(a, math.inf) for a in atoms)


def _groundings(
    task: Task, table: Objects, limit: int, reach: bool
) -> tuple[list[tuple[ActionTemplate, tuple[str, ...]]], bool]:
    """The (template, arguments) pairs of the model, by reachability where it applies,
    and whether no template reached `limit` (none can have lost groundings)."""
    if reach:
        found = reachable_bindings(task, table)
        if found is not None:
            kept: dict[str, int] = {}
            out = []
            for template, args in found:  # `limit` per template, as binding enumerates
                kept[template.name] = kept.get(template.name, 0) + 1
                if kept[template.name] <= limit:
                    out.append((template, args))
            return out, all(n < limit for n in kept.values())
    out = []
    complete = True
    for template in task.domain.actions:
        bound = [tuple(binding[p.name] for p in template.parameters) for binding in bindings(
            task, template, {}, task.initial_state, None, limit, table, optimistic=True)]
        complete = complete and len(bound) < limit
        out.extend((template, args) for args in bound)
    return out, complete


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

