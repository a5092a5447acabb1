"""A lower bound on the steps of any plan: LM-cut over the relaxed model (unit costs).

Plan improvement (improve.py) searches the states around a plan for a shorter one, and
on a small problem it often grows its neighbourhood until no new state is left, only
to show that the plan found is already as short as any: most of its cost on the small
problems that decide the median run time. A plan no longer than an admissible lower
bound needs no such search. LM-cut (Helmert and Domshlak, "Landmarks, Critical Paths
and Abstractions: What's the Difference Anyway?", ICAPS 2009) is such a bound: it
computes h_max, cuts the justification graph in front of the goal (every plan uses one
of the cut's actions), takes the cheapest cut action's cost, lowers the costs of the
cut's actions by it, and repeats until the goal costs nothing; the costs taken add up
to the bound. It reads the relaxed model planning built already (its atoms numbered
for h_add), with every action costing one step: deletes and negative preconditions are
ignored, and the model holds every grounding that can run in a state reached from the
initial state, so no plan is shorter. The rounds so far are a bound too, so it stops
once it reaches the plan's length; on a large model (thousands of actions) it is not
computed at all.
"""

from __future__ import annotations

import heapq
from collections.abc import Iterable, Sequence

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.model import Atom, GroundLiteral
    from btplan.classical.heuristic import RelaxedModel

INFINITE = float("inf")


class Cuts:
    """The relaxed model's actions as numbers, with an artificial start atom (for the
    actions that need nothing) and goal action, ready for rounds of h_max."""

    def __init__(self, pre: Sequence[Sequence[int]], add: Sequence[Sequence[int]],
                 atoms: int) -> None:
        self.start_atom, self.goal_atom = atoms, atoms + 1
        self.pre = [tuple(set(p)) or (self.start_atom,) for p in pre]
        self.add = [tuple(a) for a in add]
        self.by_pre: list[list[int]] = [[] for _ in range(atoms + 2)]
        self.unnumbered = 0
        """Atoms of the start state left unnumbered (no action here needs or adds them):
        the work a bound may take counts them as if they were, so that whether it is
        computed does not depend on how many atoms the numbering kept."""
        for i, needed in enumerate(self.pre):
            for atom in needed:
                self.by_pre[atom].append(i)

    def bound(self, start: Iterable[int], goals: Sequence[int], enough: int,
              work: int, costs: Sequence[int] | None = None) -> int:
        """The LM-cut value of reaching `goals` from the atoms `start`, in steps (or, with
        `costs`, each action's whole, non-negative cost); it stops at `enough`. Each
        round adds at least one step (or the least positive cost: an action of the cut
        costs something, as the goal zone holds the supporter of every action into it
        that costs nothing), so the rounds are bounded: 0 when they might take more
        than about `work` precondition visits. Unreachable goals give `enough`."""
        goal_action = len(self.pre)
        pre = [*self.pre, tuple(set(goals)) or (self.start_atom,)]
        add = [*self.add, (self.goal_atom,)]
        by_pre = [list(needers) for needers in self.by_pre]
        for atom in pre[goal_action]:
            by_pre[atom].append(goal_action)
        cost = [1] * goal_action + [0] if costs is None else [*costs, 0]
        least = min((c for c in cost if c > 0), default=1)
        first = {*start, self.start_atom}
        per_round = sum(len(p) for p in pre) + len(first) + self.unnumbered
        if per_round * -(-enough // least) > work:
            return 0  # the rounds `enough` may need would take too long
        total = 0
        while total < enough:
            supporter, value = _h_max(pre, add, cost, by_pre, first, self.goal_atom)
            if value == INFINITE:
                return enough
            if value == 0:
                break
            cut = _cut(add, cost, supporter, first, self.goal_atom)
            low = min(cost[i] for i in cut)
            total += low
            for i in cut:
                cost[i] -= low
        return total


def _h_max(pre: list[tuple[int, ...]], add: list[tuple[int, ...]], cost: list[int],
           by_pre: list[list[int]], start: set[int], goal: int
           ) -> tuple[list[int], float]:
    """Each action's supporter (a precondition of greatest h_max, -1: never reached),
    and the goal's h_max (Dijkstra over atoms)."""
    value = [INFINITE] * len(by_pre)
    waiting = [len(p) for p in pre]
    supporter = [-1] * len(pre)
    queue = [(0, atom) for atom in start]
    for atom in start:
        value[atom] = 0
    heapq.heapify(queue)
    done = [False] * len(by_pre)
    while queue:
        reached, atom = heapq.heappop(queue)
        if done[atom]:
            continue
        done[atom] = True
        for i in by_pre[atom]:
            waiting[i] -= 1
            if not waiting[i]:
                supporter[i] = atom  # taken last, so of greatest h_max
                through = reached + cost[i]
                for added in add[i]:
                    if through < value[added]:
                        value[added] = through
                        heapq.heappush(queue, (through, added))
    return supporter, value[goal]


def _cut(add: list[tuple[int, ...]], cost: list[int], supporter: list[int],
         start: set[int], goal: int) -> list[int]:
    """The actions leading from the atoms reached from the start (in the justification
    graph, not through the goal zone) into the goal zone (the atoms from which the goal
    is reached by actions that now cost nothing)."""
    supported: dict[int, list[int]] = {}
    achievers: dict[int, list[int]] = {}
    for i, atom in enumerate(supporter):
        if atom >= 0:
            supported.setdefault(atom, []).append(i)
            for added in add[i]:
                achievers.setdefault(added, []).append(i)
    zone, todo = {goal}, [goal]
    while todo:
        for i in achievers.get(todo.pop(), ()):
            if not cost[i] and supporter[i] not in zone:
                zone.add(supporter[i])
                todo.append(supporter[i])
    cut: list[int] = []
    seen, todo = set(start), list(start)
    while todo:
        for i in supported.get(todo.pop(), ()):
            into = False
            for added in add[i]:
                if added in zone:
                    into = True
                elif added not in seen:
                    seen.add(added)
                    todo.append(added)
            if into:
                cut.append(i)
    return cut


WORK = 30_000
"""Precondition visits the bound may take (a few ms): enough on the training set's small
problems, whose relaxed models hold a few hundred actions; mystery p09 (2,408) is left
out (its bound took 22 ms and fell short of the plan anyway)."""


def fewest_steps(relaxed: RelaxedModel, state: frozenset[Atom],
                 goal: Iterable[GroundLiteral], enough: int, work: int = WORK) -> int:
    """A lower bound on the steps of any plan from `state` to `goal`, at most `enough`.

    0 where it would not be one: when the model's actions differ in cost (a cheaper
    plan may take more steps, and improve.py weighs cost first) or when grounding cut
    the model short (`RelaxedModel.complete`); 0 too where `enough` rounds over the
    model could take more than about `work` precondition visits."""
    if not relaxed.uniform() or _too_long(relaxed, enough, 1, work):
        return 0  # every action is visited once a round: not even numbered then
    found = _numbered(relaxed, state, goal)
    if found is None:
        return enough  # no action makes a goal true: nothing reaches it
    cuts, start, goals, _ = found
    return cuts.bound(start, goals, enough, work)


def no_better_plan(relaxed: RelaxedModel, state: frozenset[Atom],
                   goal: Iterable[GroundLiteral], steps: int, cost: float,
                   work: int = WORK) -> bool:
    """Whether LM-cut proves that no plan from `state` to `goal` is better than one of
    `steps` steps costing `cost`, as improve.py weighs plans (cost first, then steps):
    with the actions' own costs it reaches `cost`, so no plan costs less, and with
    every action costing one it reaches `steps`, so none has fewer steps.

    For models whose actions differ in cost (`fewest_steps` covers the others), and
    only where every cost is a whole number: the sums are then exact, and a bound equal
    to the plan's cost means what it says. The BTPG RoboWaiter goals (costs 3 to 15)
    are such: most plans there are one or two steps and cheapest, and the bound spares
    the improvement pass, most of a call's time (bench/fixed_cost.py)."""
    if not float(cost).is_integer() or _too_long(relaxed, steps, 1, work):
        return False
    goal = tuple(goal)  # read more than once
    if steps == 1 and _cheapest_step(relaxed, state, goal, cost, work):
        return True  # what the bound below answers, known without it
    found = _numbered(relaxed, state, goal)
    if found is None:
        return True  # no plan at all
    cuts, start, goals, kept = found
    whole = relaxed.action_costs()
    costs = [whole[i] for i in kept]  # the bound reads no other (and checks its rounds)
    if not all(c.is_integer() and c >= 0 for c in costs):
        return False
    return (cuts.bound(start, goals, int(cost), work, [int(c) for c in costs]) >= cost
            and cuts.bound(start, goals, steps, work) >= steps)


def _cheapest_step(relaxed: RelaxedModel, state: frozenset[Atom],
                   goal: tuple[GroundLiteral, ...], cost: float, work: int) -> bool:
    """Whether a plan of one step costing `cost` is shown best without LM-cut's rounds:
    no action of the model adding some goal atom that `state` lacks costs less.

    Most RoboWaiter goals are planned in one such step, and the rounds were a third of
    their planning call. Where this holds, `no_better_plan` answers yes too: a goal is
    false, so every plan has a step; LM-cut is at least h_max (Helmert and Domshlak
    2009), h_max at least the cheapest achiever of any goal atom, so the bound with the
    actions' costs reaches `cost`; with unit costs its first round's cut is not empty,
    so it reaches 1. Only taken where both bounds would be computed: every cost whole
    and non-negative (each round then takes 1 at least), and the rounds' work, counted
    over the whole model (at least what the goal's part counts), within `work`."""
    if not relaxed.whole_costs():
        return False
    visits = relaxed.precondition_visits() + len(state) + 2 + len(goal)
    if visits * max(1, int(cost)) > work:
        return False
    ids = relaxed.numbered()[0]
    adders, costs = relaxed.adders(), relaxed.action_costs()
    for literal in goal:
        at = ids.get(literal.atom) if literal.positive and literal.atom not in state else None
        if at is not None and min((costs[i] for i in adders.get(at, ())),
                                  default=INFINITE) >= cost:
            return True
    return False


def _too_long(relaxed: RelaxedModel, enough: int, least: int, work: int) -> bool:
    """Whether the rounds of a bound reaching `enough`, each adding `least` at least,
    could visit more than `work` actions, or grounding cut the model short (then no
    bound holds)."""
    return (len(relaxed.actions) + 1) * -(-enough // least) > work or not relaxed.complete


def _numbered(relaxed: RelaxedModel, state: frozenset[Atom], goal: Iterable[GroundLiteral]
              ) -> tuple[Cuts, list[int], list[int], list[int]] | None:
    """The actions relevant to the goal ready for LM-cut, the state and goals as atom
    numbers, and the relevant actions' numbers in the model; None when no action makes
    a goal true that `state` lacks.

    An action is relevant when it adds a goal or a precondition of a relevant action;
    h_max of the goals, the goal zone and the cuts involve no other, so the bound is
    the same as over the whole model, in rounds over fewer actions (a RoboWaiter goal
    of one step: 1 of 174)."""
    ids, pre, add = relaxed.numbered()
    goals = []
    for literal in goal:
        if literal.positive:
            if literal.atom in ids:
                goals.append(ids[literal.atom])
            elif literal.atom not in state:
                return None
    adders = relaxed.adders()
    wanted, todo, relevant = set(goals), list(goals), set()
    while todo:
        for i in adders.get(todo.pop(), ()):
            if i not in relevant:
                relevant.add(i)
                for atom in pre[i]:
                    if atom not in wanted:
                        wanted.add(atom)
                        todo.append(atom)
    kept = sorted(relevant)
    for i in kept:
        wanted.update(add[i])
    # The relevant atoms numbered anew in the model's order (ties in h_max's queue go as
    # over the whole model), so that each round's lists are as short as the goal's part.
    local = {atom: n for n, atom in enumerate(sorted(wanted))}
    cuts = Cuts([[local[a] for a in pre[i]] for i in kept],
                [[local[a] for a in add[i]] for i in kept], len(local))
    start = [ids[a] for a in state if a in ids]
    cuts.unnumbered = len(start)
    start = [local[a] for a in start if a in local]
    cuts.unnumbered -= len(start)
    return cuts, start, [local[g] for g in goals], kept
