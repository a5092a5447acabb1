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
BOOST turns ahead. States are ints (btplan/planner/packed.py), and a child waits in
the queues as its parent's number and an action (`SearchRun`).
"""

from __future__ import annotations

import heapq
import time
from array import array
from collections.abc import Callable, Iterable, Sequence

from btplan.model import Atom, GroundAction, GroundLiteral, matches
from btplan.planner.packed import INFINITE, PackedActions, bits

MAX_STATES = 2000
"""States expanded (each one h_FF evaluation) by one search before it gives up."""

BOOST = 1000
"""Turns the preferred queues get ahead each time an estimate improves (LAMA's value)."""

SLICE = 64
"""States each search of a `Portfolio` expands in its turn."""

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
        max_bytes: int | None = None,
    ) -> list[GroundAction] | None:
        """A plan from `start` to a state where every goal literal holds, or None
        (`begin` and one `SearchRun.resume`)."""
        return self.begin(start, goal, max_states, keep, max_bytes).resume(deadline)

    def begin(
        self,
        start: frozenset[Atom],
        goal: Sequence[GroundLiteral],
        max_states: int = MAX_STATES,
        keep: Sequence[GroundLiteral] = (),
        max_bytes: int | None = None,
        portfolio: bool = False,
    ) -> SearchRun | Portfolio:
        """A search from `start` to `goal`, to be resumed until it is done.

        `max_bytes` bounds about how much memory the states expanded and the children
        waiting may take (where branching is wide, or states large).

        No step may make a `keep` literal false: the plan runs where earlier siblings
        re-check their conditions on every tick, so undoing one would send the tree
        back to them.

        Negative goal literals count for the estimates only as satisfied or not (one
        action each when not).

        With `portfolio`, the search as configured takes turns with a second one that
        guides by landmarks more (`Portfolio`).
        """
        if portfolio:
            return Portfolio(self, start, goal, max_states, keep, max_bytes)
        return SearchRun(self, start, goal, max_states, keep, max_bytes)

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

    def improved(self, estimates: tuple[int, int], best: list[float],
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

    def path(self, links: Sequence[int], via: Sequence[int], number: int) -> list[GroundAction]:
        """The actions from the start to the state numbered `number`, by way of each
        state's parent (`links`) and the action that led to it (`via`)."""
        steps: list[GroundAction] = []
        while links[number] >= 0:
            steps.append(self.actions[via[number]])
            number = links[number]
        steps.reverse()
        return steps


class Buckets:
    """A queue of entries (ints) by whole-number estimate, first in, first out within one.

    The estimates are few (h_FF and landmark counts of one search), the entries many:
    each bucket is an array of 4-byte entries (8-byte ones once an entry needs them),
    where a heap of tuples took about 100 bytes an entry, and half a million of them
    waited in a zenotravel search.
    """

    __slots__ = ("buckets", "code", "heads", "levels", "size")

    def __init__(self) -> None:
        self.buckets: dict[int, array[int]] = {}
        self.code = "I"
        """The arrays' type: 4-byte entries until one does not fit, 8-byte ones then."""
        self.heads: dict[int, int] = {}
        """How many entries each bucket has given out (they stay until it is compacted)."""
        self.levels: list[int] = []
        """The estimates that have a bucket, as a heap."""
        self.size = 0

    def __len__(self) -> int:
        return self.size

    def push(self, estimate: int, entry: int) -> None:
        """Add `entry` behind those waiting with the same estimate."""
        bucket = self.buckets.get(estimate)
        if bucket is None:
            bucket = self.buckets[estimate] = array(self.code)
            self.heads[estimate] = 0
            heapq.heappush(self.levels, estimate)
        try:
            bucket.append(entry)
        except OverflowError:  # an entry past 4 bytes: every bucket takes 8-byte ones
            self.code = "Q"
            self.buckets = {level: array("Q", held) for level, held in self.buckets.items()}
            self.buckets[estimate].append(entry)
        self.size += 1

    def pop(self) -> int:
        """The entry that came first of those with the lowest estimate."""
        estimate = self.levels[0]
        bucket = self.buckets[estimate]
        head = self.heads[estimate]
        entry = bucket[head]
        head += 1
        self.size -= 1
        if head == len(bucket):
            del self.buckets[estimate], self.heads[estimate]
            heapq.heappop(self.levels)
        elif head >= COMPACT and head * 2 >= len(bucket):
            del bucket[:head]  # what was given out, dropped once it is half the bucket
            self.heads[estimate] = 0
        else:
            self.heads[estimate] = head
        return entry

    def entries(self) -> list[int]:
        """The entries waiting, lowest estimate first (for looking inside)."""
        return [e for level in sorted(self.buckets)
                for e in self.buckets[level][self.heads[level]:]]


class Waiting:
    """The lowest h_FF each child waits with, by the child's hash, for `SearchRun`: a
    child reached again waits again only from a parent estimated lower.

    An open-addressing table in one array: a slot holds 48 bits of the (mixed) hash and
    the estimate, 8 bytes a child, where a dict of the states themselves took 600 (a
    zenotravel search generates half a million). Two states whose hashes agree in those
    bits count as one, so a child may, about once in 10^14 pairs, not wait again when
    it should; it can still be reached from another parent.
    """

    __slots__ = ("count", "mask", "table")

    def __init__(self) -> None:
        self.table = array("Q", bytes(8 * 1024))
        self.mask = 1023
        self.count = 0

    def better(self, key: int, estimate: int) -> bool:
        """Note that the state hashed `key` waits with `estimate`; False when it already
        waits with one no higher (then it need not wait again).

        `key` hashes the state's bytes: the hash of a Python int adds up its 61-bit
        chunks, so bit sets that differ by a shift of 61 atoms would count as one."""
        table, mask = self.table, self.mask
        mixed = key * MIX & BITS64  # a small state's hash is the state: spread its bits
        tag = mixed & ~LOW or LOW + 1
        estimate = min(estimate, LOW)
        slot = (tag >> 16) & mask
        while True:
            held = table[slot]
            if not held:
                table[slot] = tag | estimate
                self.count += 1
                if self.count * 2 > mask:
                    self._grow()
                return True
            if (held & ~LOW) == tag:
                if (held & LOW) <= estimate:
                    return False
                table[slot] = tag | estimate
                return True
            slot = (slot + 1) & mask

    def _grow(self) -> None:
        old = self.table
        self.mask = mask = self.mask * 2 + 1
        self.table = table = array("Q", bytes(8 * (mask + 1)))
        for held in old:
            if held:
                slot = (held >> 16) & mask
                while table[slot]:
                    slot = (slot + 1) & mask
                table[slot] = held


LOW = (1 << 16) - 1
"""A slot's low 16 bits: the estimate (capped); the 48 above are the mixed hash's."""

MIX = 0x9E3779B97F4A7C15
"""An odd multiplier (2^64 over the golden ratio): multiplying by it mod 2^64 maps
distinct hashes to distinct values and spreads low bits into the high ones."""

BITS64 = (1 << 64) - 1


COMPACT = 4096
"""Entries a bucket gives out before it may drop them (`Buckets.pop`)."""

STATE_BYTES = 200
"""About what an expanded state costs beside its bits: its entries in the table of
states, the lists of parents, actions and landmarks, and the int's header."""

ENTRY_BYTES = 9
"""About what a waiting entry costs at most: 8 bytes in its bucket's array (4 while the
numbers fit), and the array's slack."""


class SearchRun:
    """One search, which can stop at a deadline and go on later where it stopped.

    Offline planning gives the whole-goal search a slice of time as soon as
    backchaining's first strategy fails, and the rest after the other strategies.

    Evaluation is deferred, and so is the state: a child waits in the queues as its
    parent's number and the action (one int), and becomes a state when it is taken out.
    Only the states taken out are kept (numbered, with their parent and action), so a
    search keeps a few bytes for each child it generates (`Buckets`, `Waiting`) and a
    state for each it expands: zenotravel p03's whole-goal search kept 227 MB of states
    and queue entries as sets of tuples, and keeps 20 MB so. A child reached again
    before it is taken out waits again only from a parent with a lower h_FF; the first
    of its entries taken out is expanded, with that entry's parent.
    """

    def __init__(self, engine: SubgoalSearch, start: frozenset[Atom],
                 goal: Sequence[GroundLiteral], max_states: int,
                 keep: Sequence[GroundLiteral], max_bytes: int | None,
                 landmark_preferred: bool | None = None,
                 landmark_orders: bool | None = None, reasonable: bool = True) -> None:
        self.engine = engine
        self.landmark_preferred = (engine.landmark_preferred if landmark_preferred is None
                                   else landmark_preferred)
        if landmark_orders is None:
            landmark_orders = engine.landmark_orders
        self.max_states, self.max_bytes = max_states, max_bytes
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
        self.start = first = packed.encode(start)
        self.numbered: dict[int, int] = {}
        """Each state taken out of the queues (expanded, or a dead end), by its number."""
        self.states: list[int] = []
        self.links = array("l")
        """Each numbered state's parent's number (-1: the start)."""
        self.via = array("l")
        """The action that led to each numbered state from its parent (-1: the start)."""
        self.passed: list[int] = []
        """The landmarks each numbered state's path reached (0 for a dead end)."""
        self.width = len(engine.actions) + 1
        """Entries are parent number * width + action number + 1; 0 is the start."""
        self.state_bytes = len(packed.atoms) // 8 + STATE_BYTES
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
        self.before_start = every & first if ordered else 0
        """What the start's "parent" passed: with the orders, the landmarks the start
        has, so that they too count again when needed again (and so do the goals)."""
        self.queues = [Buckets() for _ in range(4 if self.marks else 2)]
        self.turns = [0] * len(self.queues)
        self.best = [INFINITE] * 2
        self.queues[0].push(0, 0)
        self.waits = Waiting()

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
        queues, turns, numbered, passed_of = self.queues, self.turns, self.numbered, self.passed
        width, banned, apply, waits = self.width, self.banned, packed.apply, self.waits
        size = (len(packed.atoms) + 7) // 8
        while not self.done:
            chosen = _turn(queues, turns)
            if chosen is None:
                self._finish(exhausted=True)
                break
            entry = queues[chosen].pop()
            if entry:
                parent, action = divmod(entry, width)
                action -= 1
                state = apply(action, self.states[parent])
                before = passed_of[parent]
            else:
                parent, action, state, before = -1, -1, self.start, self.before_start
            if state in numbered:
                continue  # expanded already, or a dead end
            number = numbered[state] = len(self.states)
            self.states.append(state)
            self.links.append(parent)
            self.via.append(action)
            if state & positive == positive and not state & negative:
                self.passed.append(0)
                self._finish(plan=engine.path(self.links, self.via, number))
                break
            true = bits(state)
            h, relaxed = packed.h_ff(true, numbers)
            if h == INFINITE:
                self.passed.append(0)  # a dead end: never looked at again
                continue
            h += (state & negative).bit_count()
            passed = self.progress(before, state)
            self.passed.append(passed)
            future = self.future(state, passed) if marks else 0
            estimates = (int(h), future.bit_count() if marks else int(h))
            if engine.improved(estimates, self.best, turns):
                self.better_at = self.expanded
            self.expanded = engine.expanded = self.expanded + 1
            if self.expanded >= self.max_states or self.full():
                self._finish()
                break
            applicable = packed.applicable(state, true)
            if self.landmark_preferred and future & ~state:
                adds, wanted = packed.add_mask, future & ~state
                relaxed = relaxed | {i for i in applicable if adds[i] & wanted}
            base, waits_with = number * width + 1, estimates[0]
            for i in applicable:
                if i in banned:
                    continue
                child = apply(i, state)
                if child in numbered or not waits.better(hash(child.to_bytes(size)),
                                                         waits_with):
                    continue  # expanded, or waiting already from a parent no worse
                for q in range(0, len(queues), 2):
                    estimate = estimates[q // 2]
                    queues[q].push(estimate, base + i)
                    if i in relaxed:
                        queues[q + 1].push(estimate, base + i)
            if deadline is not None and self.expanded % 32 == 0 \
                    and time.perf_counter() > deadline or self.expanded == stop:
                break
        return self.plan

    def release(self) -> None:
        """Drop the states and entries kept: the search is over (its plan, counts and
        outcome stay), and the memory goes to what planning does next."""
        self.done = True
        self.queues, self.states, self.numbered, self.passed = [], [], {}, []
        self.links, self.via, self.waits = array("l"), array("l"), Waiting()

    def full(self) -> bool:
        """Whether the states and entries kept have reached `max_bytes`."""
        return self.max_bytes is not None and self.bytes > self.max_bytes

    @property
    def bytes(self) -> int:
        """About the memory the states, entries and hashes kept take (STATE_BYTES,
        ENTRY_BYTES, and 8 bytes a slot of `Waiting`)."""
        return (len(self.states) * self.state_bytes + 8 * (self.waits.mask + 1)
                + ENTRY_BYTES * sum(len(queue) for queue in self.queues))

    @property
    def stored(self) -> int:
        """States kept (expanded or dead ends) and entries waiting."""
        return len(self.states) + sum(len(queue) for queue in self.queues)


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
                 keep: Sequence[GroundLiteral], max_bytes: int | None) -> None:
        half = None if max_bytes is None else max_bytes // 2
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

    def release(self) -> None:
        """Drop both searches' states and entries (`SearchRun.release`)."""
        self.done = True
        for run in self.runs:
            run.release()

    @property
    def expanded(self) -> int:
        """States expanded by both searches."""
        return sum(run.expanded for run in self.runs)

    @property
    def stored(self) -> int:
        """States kept by both searches, expanded or waiting."""
        return sum(run.stored for run in self.runs)


def _turn(queues: list[Buckets], turns: list[int]) -> int | None:
    """The non-empty queue whose turn it is (fewest turns taken, boosts counted)."""
    chosen = None
    for q, queue in enumerate(queues):
        if queue and (chosen is None or turns[q] < turns[chosen]):
            chosen = q
    if chosen is not None:
        turns[chosen] += 1
    return chosen
