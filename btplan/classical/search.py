"""The last resort: a complete search, for one stuck condition or for the whole goal.

When backchaining finds no conflict-free place for the subtree achieving a condition,
or every achiever of it is circular, the paper stops. btplan then searches, from the
state the tree reached, for a plan that makes the condition true while keeping what
the enclosing sequences already hold, and btplan/planner/rescue.py turns that plan
into a reactive subtree; when backchaining fails as a whole, the same search plans the
whole goal (btplan/acting/offline/planning.py). The search sees every grounding of the relaxed
model, so it is only bounded by its budget of states; it is the exception, and the
summary counts it.

The search is a satisficing planner's greedy best-first search (as in LAMA, Richter
and Westphal 2010): deferred evaluation (a state is evaluated when taken from a queue,
with its parent's estimate until then), two estimates (h_FF and the count of fact
landmarks not yet reached on the path), and for each a second queue holding only the
children of preferred actions (those of the relaxed plan that can run now); the
queues take turns, and every time an estimate improves the preferred queues get
BOOST turns ahead. States are ints (btplan/classical/packed.py).
"""

from __future__ import annotations

import heapq
import itertools
import time
from collections.abc import Callable, Iterable, Sequence

from btplan.model import Atom, GroundAction, GroundLiteral, matches
from btplan.classical.packed import INFINITE, PackedActions, bits

MAX_STATES = 2000
"""States expanded (each one h_FF evaluation) by one search before it gives up."""

BOOST = 1000
"""Turns the preferred queues get ahead each time an estimate improves (LAMA's value)."""

SLICE = 64
"""States each search of a `Portfolio` expands in its turn."""

Parents = dict[int, tuple[int, int] | None]


def spell_out(actions: Sequence[GroundAction], atoms: Iterable[Atom]) -> list[GroundAction]:
    """`actions` with their wildcard deletes (`not near(_)`) written out as the `atoms`
    they match: the search's packed states know plain deletes only, and leaves out an
    action with a pattern. Exact for every atom of `atoms`; the caller gives every atom
    a state of the search can hold (the start's, and those the actions add)."""
    known = set(atoms)
    for action in actions:
        known.update(action.add)
    by_predicate: dict[str, list[Atom]] = {}
    for atom in known:
        by_predicate.setdefault(atom.predicate, []).append(atom)
    out: list[GroundAction] = []
    for action in actions:
        if not action.delete_patterns:
            out.append(action)
            continue
        hit = {a for p in action.delete_patterns for a in by_predicate.get(p.predicate, ())
               if matches(p, a) and a not in action.add}
        out.append(action.model_copy(update={
            "delete": tuple(dict.fromkeys([*action.delete, *sorted(hit, key=str)])),
            "delete_patterns": ()}))
    return out


class SubgoalSearch:
    """Lazy greedy best-first search with h_FF, landmarks and preferred actions."""

    def __init__(self, actions: Sequence[GroundAction]) -> None:
        self.actions = [a for a in actions if not a.delete_patterns]
        self.packed = PackedActions(self.actions)
        self.expanded = 0
        """States the last search expanded (for the failure message)."""
        self.exhausted = False
        """Whether the last search ran out of states to look at (no plan exists)."""
        self.use_landmarks = True
        """Whether the landmark queues take part (off: h_FF and its preferred queue only)."""
        self.boost = BOOST
        self.landmark_orders = False
        """Whether landmarks count again when needed again and goals reached too early
        count as not reached (LAMA's orders; off: measured mixed, see
        docs/results/planner-search.md)."""
        self.exclusive: Callable[[Atom, Atom], bool] | None = None
        """Whether two atoms can never hold together (mutexes), for the reasonable
        orders of landmarks; without it there are none."""
        self.landmark_preferred = False
        """Whether actions that make a landmark still to reach true are preferred too
        (beside the relaxed plan's), see `Portfolio`."""

    def search(
        self,
        start: frozenset[Atom],
        goal: Sequence[GroundLiteral],
        max_states: int = MAX_STATES,
        deadline: float | None = None,
        keep: Sequence[GroundLiteral] = (),
        max_stored: int | None = None,
    ) -> list[GroundAction] | None:
        """A plan from `start` to a state where every goal literal holds, or None
        (`begin` and one `SearchRun.resume`)."""
        return self.begin(start, goal, max_states, keep, max_stored).resume(deadline)

    def begin(
        self,
        start: frozenset[Atom],
        goal: Sequence[GroundLiteral],
        max_states: int = MAX_STATES,
        keep: Sequence[GroundLiteral] = (),
        max_stored: int | None = None,
        portfolio: bool = False,
    ) -> SearchRun | Portfolio:
        """A search from `start` to `goal`, to be resumed until it is done.

        `max_stored` bounds the states kept, expanded or waiting (memory, where
        branching is wide). A state reached again before it is expanded waits again
        only when its new parent's h_FF is lower, and then takes that parent.

        No step may make a `keep` literal false: the plan runs where earlier siblings
        re-check their conditions on every tick, so undoing one would send the tree
        back to them.

        Negative goal literals count for the estimates only as satisfied or not (one
        action each when not).

        With `portfolio`, the search as configured takes turns with a second one that
        guides by landmarks more (`Portfolio`).
        """
        if portfolio:
            return Portfolio(self, start, goal, max_states, keep, max_stored)
        return SearchRun(self, start, goal, max_states, keep, max_stored)

    def banned(self, keep: Sequence[GroundLiteral]) -> set[int]:
        """The actions that would make a `keep` literal false."""
        if not keep:
            return set()
        packed = self.packed
        held = packed.literal_mask(k.atom for k in keep if k.positive)
        absent = packed.literal_mask(k.atom for k in keep if not k.positive)
        return {i for i in range(len(self.actions))
                if packed.del_mask[i] & held & ~packed.add_mask[i]
                or packed.add_mask[i] & absent}

    def improved(self, estimates: tuple[float, float], best: list[float],
                 turns: list[int]) -> bool:
        """Note better estimates (whether there are any); each improvement moves the
        preferred queues ahead."""
        better = False
        for k, value in enumerate(estimates[:len(turns) // 2]):
            if value < best[k]:
                best[k], better = value, True
                for q in range(1, len(turns), 2):
                    turns[q] -= self.boost
        return better

    def path(self, parents: Parents, state: int) -> list[GroundAction]:
        """The actions from the start to `state`, by way of each state's parent."""
        steps: list[GroundAction] = []
        link = parents[state]
        while link is not None:
            state, i = link
            steps.append(self.actions[i])
            link = parents[state]
        steps.reverse()
        return steps



class SearchRun:
    """One search, which can stop at a deadline and go on later where it stopped.

    Offline planning gives the whole-goal search a slice of time as soon as
    backchaining's first strategy fails, and the rest after the other strategies.
    """

    def __init__(self, engine: SubgoalSearch, start: frozenset[Atom],
                 goal: Sequence[GroundLiteral], max_states: int,
                 keep: Sequence[GroundLiteral], max_stored: int | None,
                 landmark_preferred: bool | None = None,
                 landmark_orders: bool | None = None, reasonable: bool = True) -> None:
        self.engine = engine
        self.landmark_preferred = (engine.landmark_preferred if landmark_preferred is None
                                   else landmark_preferred)
        if landmark_orders is None:
            landmark_orders = engine.landmark_orders
        self.max_states, self.max_stored = max_states, max_stored
        self.done = False
        """Whether the search is over: a plan found, no plan exists, or a bound reached."""
        self.plan: list[GroundAction] | None = None
        self.expanded = 0
        self.better_at = 0
        """The states expanded when an estimate last improved."""
        self.exhausted = False
        """Whether the search ran out of states to look at (no plan exists)."""
        engine.expanded, engine.exhausted = 0, False
        packed = engine.packed
        test = packed.goal_test(goal, start)
        first = packed.encode(start)
        self.parents: Parents = {first: None}  # each state's best parent so far
        self.keys: dict[int, float] = {first: 0.0}  # the h_FF each waiting state waits with
        self.reached: dict[int, int] = {}  # the landmarks each expanded state's path reached
        self.positive, self.negative, self.numbers = test or (0, 0, [])
        if test is None:
            self._finish(exhausted=True)
        self.banned = engine.banned(keep) | packed.static_misses(start)
        every = (packed.landmarks(bits(first), self.numbers)
                 if engine.use_landmarks and not self.done else 0)
        self.marks = every & ~first
        """The landmarks the start lacks: each counts until the path reaches it."""
        self.again = self.positive
        """The landmarks that count again when the path reached them and they are false
        now: the goals, and (`needed`) those ordered before a landmark not yet reached."""
        ordered = landmark_orders and bool(self.marks)
        needed = packed.necessary(every, self.banned) if ordered else {}
        self.needed = list(needed.items())
        exclusive = engine.exclusive
        self.orders = list(packed.reasonable(
            self.marks, self.numbers, needed, lambda a, b: exclusive(
                packed.atoms[a], packed.atoms[b]), self.banned).items()) \
            if ordered and reasonable and exclusive is not None else []
        """Goals and the landmarks they come after: a goal reached before them is not
        yet counted as reached."""
        # What the start's "parent" passed: with the orders, the landmarks the start
        # has, so that they too count again when needed again (and so do the goals).
        self.reached[-1] = every & first if ordered else 0
        self.queues: list[list[tuple[float, int, int, int, int]]] = [
            [] for _ in range(4 if self.marks else 2)]
        self.turns = [0] * len(self.queues)
        self.best = [INFINITE] * 2
        self.counter = itertools.count()
        self.queues[0].append((0.0, next(self.counter), first, -1, -1))

    def progress(self, passed: int, state: int) -> int:
        """The landmarks reached on the path to `state`, its parent's path having
        reached `passed`: those true in it, but a goal whose landmarks ordered before
        it (`orders`) are neither reached before nor true in it."""
        new = state & self.marks & ~passed
        if new and self.orders:
            now = passed | new
            for goal, before in self.orders:
                if new >> goal & 1 and before & ~now:
                    new &= ~(1 << goal)
        return passed | new

    def future(self, state: int, passed: int) -> int:
        """The landmarks still to reach, as a mask: those not yet reached on the path,
        and those reached, false in `state` and needed again (Richter and Westphal 2010)."""
        missing = self.marks & ~passed
        again = self.again
        for atom, before in self.needed:
            if missing >> atom & 1:
                again |= before
        return missing | again & passed & ~state

    def count(self, state: int, passed: int) -> int:
        """The landmark estimate: how many landmarks are still to reach (`future`)."""
        return self.future(state, passed).bit_count()

    def _finish(self, exhausted: bool = False, plan: list[GroundAction] | None = None) -> None:
        self.done, self.exhausted, self.plan = True, exhausted, plan
        self.engine.exhausted = exhausted

    def resume(self, deadline: float | None = None,
               states: int | None = None) -> list[GroundAction] | None:
        """Search on until a plan is found (returned), the search is over, `deadline`,
        or (when given) `states` more states are expanded."""
        stop = None if states is None else self.expanded + states
        packed, engine = self.engine.packed, self.engine
        positive, negative, numbers, marks = self.positive, self.negative, self.numbers, self.marks
        queues, turns, parents, reached = self.queues, self.turns, self.parents, self.reached
        keys = self.keys
        while not self.done:
            chosen = _turn(queues, turns)
            if chosen is None:
                self._finish(exhausted=True)
                break
            _, _, state, parent, action = heapq.heappop(queues[chosen])
            if state in reached:
                continue
            if state & positive == positive and not state & negative:
                self._finish(plan=engine.path(parents, state))
                break
            true = bits(state)
            h, relaxed = packed.h_ff(true, numbers)
            if h == INFINITE:
                reached[state] = 0  # a dead end: never looked at again
                continue
            h += (state & negative).bit_count()
            passed = reached[state] = self.progress(reached[parent], state)
            future = self.future(state, passed) if marks else 0
            estimates = (h, future.bit_count() if marks else h)
            if engine.improved(estimates, self.best, turns):
                self.better_at = self.expanded
            self.expanded = engine.expanded = self.expanded + 1
            if self.expanded >= self.max_states or (
                    self.max_stored is not None and len(parents) > self.max_stored):
                self._finish()
                break
            applicable = packed.applicable(state, true)
            if self.landmark_preferred and future & ~state:
                adds, wanted = packed.add_mask, future & ~state
                relaxed = relaxed | {i for i in applicable if adds[i] & wanted}
            bound = self.max_stored
            for i in applicable:
                if i in self.banned:
                    continue
                if bound is not None and len(parents) > bound:
                    break  # one state's successors may be thousands: stop at the bound
                child = packed.apply(i, state)
                if child in parents and (child in reached or keys[child] <= h):
                    continue  # waiting already, from a parent estimated no worse
                parents[child], keys[child] = (state, i), h
                number = next(self.counter)
                for q in range(0, len(queues), 2):
                    estimate = estimates[q // 2]
                    heapq.heappush(queues[q], (estimate, number, child, state, i))
                    if i in relaxed:
                        heapq.heappush(queues[q + 1], (estimate, number, child, state, i))
            if deadline is not None and self.expanded % 32 == 0 \
                    and time.perf_counter() > deadline or self.expanded == stop:
                break
        return self.plan

    @property
    def stored(self) -> int:
        """States kept, expanded or waiting."""
        return len(self.parents)


class Portfolio:
    """Two searches taking turns of `SLICE` states; the first plan found is the answer.

    Each turn goes to the search whose estimates improved fewest states ago (the
    first on ties), so a search that keeps improving keeps the time.

    The first is the search as configured. The second also prefers the actions that
    make a landmark still to reach true, and counts a reached landmark again while it
    is false and every achiever of a landmark not yet reached needs it (the orders of
    `SubgoalSearch.landmark_orders`, without the reasonable orders of goals). With
    only the relaxed plan's actions preferred, parking's search stalls (best h_FF 18
    after 4,096 states on p02) while its landmark count drops: it reaches landmarks
    in an order that undoes them. The second search solves parking p01, p02 and p04
    in 888, 471 and 1,792 states, but on barman p01 and hiking p03 finds nothing in
    3,000 where the first needs 2,328 and 1,584: neither is best everywhere, so they
    share the time (docs/results/planner-search.md).
    """

    def __init__(self, engine: SubgoalSearch, start: frozenset[Atom],
                 goal: Sequence[GroundLiteral], max_states: int,
                 keep: Sequence[GroundLiteral], max_stored: int | None) -> None:
        half = None if max_stored is None else max_stored // 2
        self.runs = [SearchRun(engine, start, goal, max_states, keep, half),
                     SearchRun(engine, start, goal, max_states, keep, half,
                               landmark_preferred=True, landmark_orders=True,
                               reasonable=False)]
        self.plan: list[GroundAction] | None = None
        self.exhausted = any(run.exhausted for run in self.runs)
        self.done = self.exhausted

    def resume(self, deadline: float | None = None) -> list[GroundAction] | None:
        """Search on, in turns, until a plan is found (returned), both searches are
        over (or one finds that no plan exists), or `deadline`."""
        while not self.done:
            waiting = [run for run in self.runs if not run.done]
            if not waiting:
                self.done = True
                break
            run = min(waiting, key=lambda run: run.expanded - run.better_at)
            self.plan = run.resume(deadline, SLICE)
            self.exhausted = run.exhausted
            if self.plan is not None or self.exhausted:
                self.done = True
            elif deadline is not None and time.perf_counter() > deadline:
                break
        return self.plan

    @property
    def expanded(self) -> int:
        """States expanded by both searches."""
        return sum(run.expanded for run in self.runs)

    @property
    def stored(self) -> int:
        """States kept by both searches, expanded or waiting."""
        return sum(run.stored for run in self.runs)


def _turn(queues: list[list[tuple[float, int, int, int, int]]], turns: list[int]) -> int | None:
    """The non-empty queue whose turn it is (fewest turns taken, boosts counted)."""
    chosen = None
    for q, queue in enumerate(queues):
        if queue and (chosen is None or turns[q] < turns[chosen]):
            chosen = q
    if chosen is not None:
        turns[chosen] += 1
    return chosen
