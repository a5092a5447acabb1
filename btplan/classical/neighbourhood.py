"""The states around a plan's trajectory, for plan-neighbourhood search (improve.py).

A task is packed as bit masks (btplan/classical/packed.py); the neighbourhood of a plan
is every state within `depth` steps of a state the plan passes through, found breadth
first and kept with its edges, within a budget of states, memory and time. The cheapest
path from the initial state to a goal state through it is then a plan at least as good
as the one it was grown around.
"""

from __future__ import annotations

import heapq
import time
from array import array
from collections.abc import Callable, Sequence

from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.classical.packed import PackedActions
from btplan.records import record

MAX_STATES = 50_000
"""States one neighbourhood may hold, at most. On the training domains' small problems the
neighbourhoods that shortened a plan held at most 31,000 states but one (hiking p03: two
steps fewer at 163,000); a neighbourhood this full that finds nothing ends the search."""

MAX_BYTES = 6 << 20
"""Bytes the states of one neighbourhood may take: a state is an int of one bit per
atom (a 100-block blocksworld's: 1.3 kB), plus what its slot, its lists and its edges
cost (`STATE_OVERHEAD`). With this budget zenotravel p03 and parking p04 stop at 36,000
and 30,000 states instead of 50,000, and every training problem keeps its plan; with 5 MB
barman p01's is a step longer."""

STATE_OVERHEAD = 90
"""Bytes a state costs beyond its bits, about: the int's header, its slot in the table,
its places in the lists, its share of the edges (measured 109-161 bytes a state in all on
zenotravel, transport, visit-all and barman, 50,000 states each)."""

EDGES_PER_STATE = 16
"""Edges kept, on average, per state of the budget (8 bytes each, as arrays)."""

SMALL_STATES = 4096
"""States numbered by a dict, at most, before the table takes over: the dict costs about
85 bytes a state, 350 kB at this size, and numbers a child several times faster."""

CHECK_EVERY = 256
"""States generated between two looks at the clock."""


class OutOfTime(Exception):
    """The deadline passed (or stop was asked for) while a neighbourhood was explored."""


@record(frozen=True)
class Limits:
    """How far plan-neighbourhood search may go: states per neighbourhood, a deadline
    (a time.perf_counter() value), and a callback that says to stop."""

    max_states: int = MAX_STATES
    """States one neighbourhood may hold (`states_for` bounds them by memory too)."""
    deadline: float | None = None
    stop: Callable[[], bool] | None = None

    @staticmethod
    def states_for(atoms: int) -> int:
        """MAX_STATES, or fewer where states of `atoms` bits would take more than
        MAX_BYTES."""
        return min(MAX_STATES, MAX_BYTES // (atoms // 8 + STATE_OVERHEAD))

    def passed(self) -> bool:
        """Whether the search must stop now: the deadline (a time.perf_counter() value) passed,
        or `stop` says so. Explorations ask it every CHECK_EVERY states, not on each."""
        return ((self.deadline is not None and time.perf_counter() > self.deadline)
                or (self.stop is not None and self.stop()))


class PlanSpace:
    """A task packed for improving its plans: start, goal test, actions that can run."""

    def __init__(self, packed: PackedActions, start: frozenset[Atom],
                 goal: Sequence[GroundLiteral]) -> None:
        self.packed = packed
        self.start = packed.encode(start)
        test = packed.goal_test(goal, start)
        self.positive, self.negative = (test[0], test[1]) if test is not None else (-1, 0)
        self.reachable = test is not None
        self.banned = packed.static_misses(start)
        self.costs = [a.cost for a in packed.actions]
        self.unit = len(set(self.costs)) <= 1
        self.generator = Successors(packed, self.banned)

    def encode(self, plan: Sequence[GroundAction]) -> list[int] | None:
        """The plan as action numbers; None when an action is not among the packed ones.

        Only the plan's actions are looked up: a table of every action's key took 15 MB
        of parking p04's 33,000 groundings."""
        wanted = {a.key for a in plan}
        numbers: dict[tuple[str, tuple[str, ...]], int] = {}
        for i, action in enumerate(self.packed.actions):
            key = (action.name, action.args)
            if key in wanted:
                numbers[key] = i
        out = [numbers.get(a.key) for a in plan]
        return None if any(n is None for n in out) else [n for n in out if n is not None]

    def goal(self, state: int) -> bool:
        """Whether the packed `state` satisfies the goal: every positive bit set, no negative one.
        Never, when the goal could not be packed (`reachable` is False)."""
        return state & self.positive == self.positive and not state & self.negative

    def runs(self, i: int, state: int) -> bool:
        """Whether action number `i` can run in the packed `state`: its positive preconditions set
        and none of its negative ones. Static preconditions are `banned`'s part."""
        packed = self.packed
        return (state & packed.pre_mask[i] == packed.pre_mask[i]
                and not state & packed.neg_mask[i])

    def trajectory(self, plan: Sequence[int]) -> list[int]:
        """The states the plan passes through, the initial one first."""
        states = [self.start]
        for i in plan:
            states.append(self.packed.apply(i, states[-1]))
        return states

    def valid(self, plan: Sequence[int]) -> bool:
        """Whether `plan` (action numbers) runs step by step from the start, with no banned
        action, and ends where the goal holds: no improvement is accepted otherwise."""
        state = self.start
        for i in plan:
            if i in self.banned or not self.runs(i, state):
                return False
            state = self.packed.apply(i, state)
        return self.goal(state)

    def measure(self, plan: Sequence[int]) -> tuple[float, int]:
        """(cost, steps): what `improve` makes smaller, cost first."""
        return sum(self.costs[i] for i in plan), len(plan)



class Successors:
    """The actions that can run in a state, found through two of their preconditions.

    PackedActions.applicable serves the search, which asks about one state after a
    close neighbour: it keeps each action's count of preconditions still false for the
    last state asked and updates it by the atoms that differ. A neighbourhood is grown
    breadth first, over states far apart, so here each action hangs under its least
    shared precondition, then under its next least shared one, and the actions tested
    are those with two preconditions true (a plane in a city, with every fuel level and
    destination, is not tested in vain); `banned` actions are left out.
    """

    def __init__(self, packed: PackedActions, banned: set[int]) -> None:
        self.packed = packed
        shared = [0] * len(packed.atoms)
        for pre in packed.pre:
            for atom in pre:
                shared[atom] += 1
        count = len(packed.atoms)
        rank = [uses * count + atom for atom, uses in enumerate(shared)]  # least shared first
        masks = list(zip(range(len(packed.pre)), packed.pre_mask, packed.neg_mask))
        self.free: list[tuple[int, int, int]] = []
        """The actions with no positive precondition, with their masks as in `_runs`."""
        grouped: list[dict[int, list[int]] | None] = [None] * count
        for i, pre in enumerate(packed.pre):
            if i in banned:
                continue
            if not pre:
                self.free.append(masks[i])
                continue
            first, *rest = sorted(pre, key=rank.__getitem__)
            groups = grouped[first]
            if groups is None:
                groups = grouped[first] = {}
            groups.setdefault(rest[0] if rest else -1, []).append(i)
        self.table = {1 << atom: _runs(groups, masks) for atom, groups in enumerate(grouped)
                      if groups}
        """Each anchor's actions (by the anchor's bit), as `_runs` has them."""
        self.anchors = sum(self.table)
        """The atoms some action hangs under: the only set bits a state is read by."""
        self.keep = [~mask for mask in packed.del_mask]
        """Each action's complement of its deletes, once, not once a child."""

    def successors(self, state: int) -> tuple[list[int], list[int]]:
        """The actions that can run in `state`, and the states each leads to.

        The same actions in the same order as testing group by group: the free ones,
        then anchors lowest first, each anchor's groups as `_runs` keeps them. Their
        runs are gathered, then tested at once: a comprehension per run cost a call
        each, a quarter of the time of a state with one or two actions a run."""
        free = self.free  # no positive precondition: only the negative ones to test
        actions = [i for i, _, neg in free if not state & neg] if free else []
        candidates: list[tuple[int, int, int]] = []
        table = self.table
        rest = state & self.anchors
        while rest:
            low = rest & -rest
            rest ^= low
            for second, run in table[low]:
                if state & second == second:
                    candidates += run
        actions += [i for i, pre, neg in candidates if state & pre == pre and not state & neg]
        keep, add = self.keep, self.packed.add_mask
        return actions, [state & keep[i] | add[i] for i in actions]


def _runs(groups: dict[int, list[int]], masks: list[tuple[int, int, int]]
          ) -> list[tuple[int, list[tuple[int, int, int]]]]:
    """An anchor's groups (second precondition: actions, in the order they came), as
    runs: (bit of the second precondition, or 0, and each action with its masks:
    `masks`, by action).

    A group of one or two actions joins the run before it, untested: testing its
    actions costs about what testing its second precondition would, and each run
    costs a turn of the loop (groups are one or two actions in logistics and
    RoboWaiter). The order of the actions is kept: it is the order the children are
    numbered in."""
    runs: list[tuple[int, list[tuple[int, int, int]]]] = []
    for second, group in groups.items():
        members = list(map(masks.__getitem__, group))
        if len(group) <= 2 or second < 0:
            if runs and runs[-1][0] == 0:
                runs[-1][1].extend(members)
            else:
                runs.append((0, members))
        else:
            runs.append((1 << second, members))
    return runs


class Neighbourhood:
    """The states within `depth` steps of a trajectory, grown one step at a time.

    States are numbered as they are found, and expanded in that order (the trajectory's,
    then each layer's); each expanded state keeps its edges (the actions that can run in
    it and the numbers of the states they lead to), so the cheapest path is found
    without generating successors again. The edges of all states are two flat arrays
    of 4-byte numbers, the states' share of them a third (`first`): a dict of arrays per
    state, and a dict of parents per search, took 500 bytes a state, and a visit-all
    neighbourhood of 50,000 states 25 MB.
    """

    def __init__(self, space: PlanSpace, trajectory: list[int], limits: Limits,
                 previous: Neighbourhood | None = None) -> None:
        self.space = space
        self.limits = limits
        self.max_states = limits.max_states
        self.states: list[int] = []
        self._index: dict[int, int] | None = {}
        """States to numbers while the neighbourhood is small (SMALL_STATES): a child is
        looked up by one C call, map(dict.get), where the table below costs a Python
        loop per child; then the table takes over (`_leave_index`)."""
        self._slots = array("i")
        """Open addressing by the hash of a state's bytes: its number + 1 (0: free), a
        state found by comparing it with `states` (a dict of states to numbers took 85
        bytes a state, these 8 to 16)."""
        self._mask = 0
        self._size = (len(space.packed.atoms) + 7) // 8
        self.first = array("l", [0])
        """Where each expanded state's edges start in `actions` and `targets` (and,
        last, where the next one's will): state n's are first[n] to first[n + 1]."""
        self.actions = array("i")
        self.targets = array("i")
        self.frontier = self._number_children(list(dict.fromkeys(trajectory)), [])
        self.depth = 0
        self.full = False
        """The state budget ran out: the neighbourhood cannot grow any more."""
        self._ticks = 0
        self._previous = previous if previous is not None and previous.small else None
        """The neighbourhood grown before this one, around the plan this one's trajectory
        bettered, while both are small: the states it expanded are not expanded again
        but read from its edges (most are, around a trajectory a few steps apart; on
        logistics that was two expansions in five)."""
        if previous is not None:
            previous._previous = None  # no chain of them

    @property
    def small(self) -> bool:
        """Whether the states are still numbered by a dict (SMALL_STATES at most)."""
        return self._index is not None

    def _successors(self, state: int) -> tuple[list[int], list[int]]:
        """The actions that can run in `state` and the states they lead to: as the
        previous neighbourhood found them, when it expanded `state`."""
        previous = self._previous
        if previous is not None:
            assert previous._index is not None
            number = previous._index.get(state)
            if number is not None and number < len(previous.first) - 1:
                start, end = previous.first[number], previous.first[number + 1]
                return (previous.actions[start:end].tolist(),
                        list(map(previous.states.__getitem__, previous.targets[start:end])))
        return self.space.generator.successors(state)

    def _number_children(self, children: list[int], layer: list[int]) -> list[int]:
        """The children's numbers, in order; the new ones numbered as they come and
        added to `layer` too (a child met twice is new once)."""
        index = self._index
        if index is None:
            return self._number_in_table(children, layer)
        numbers = list(map(index.get, children))
        count = len(children)
        numbers.append(None)  # so that index() finds one: the end
        k = numbers.index(None)
        if k < count:
            states, add = self.states, index.setdefault
            size = len(states)
            while k < count:  # the children not known before this state, by index() in C
                child = children[k]
                number = numbers[k] = add(child, size)
                if number == size:  # new, not a sibling met just before
                    states.append(child)
                    layer.append(number)
                    size += 1
                k = numbers.index(None, k + 1)
            if size > SMALL_STATES:
                self._leave_index()
        numbers.pop()
        return numbers  # type: ignore[return-value]  # no None is left

    def _leave_index(self) -> None:
        """Number states by the table from now on: the dict has grown to where it
        costs more memory than its speed is worth."""
        self._index = None
        self._previous = None  # what it holds is no longer small beside this one
        self._mask = 1023
        while 2 * len(self.states) > self._mask:
            self._mask = 2 * self._mask + 1
        self._fill_slots()

    def _number_in_table(self, children: list[int], layer: list[int]) -> list[int]:
        """`_number_children` by open addressing, inline: one call per child cost a
        third of the time of growing."""
        states, slots, mask, size = self.states, self._slots, self._mask, self._size
        numbers = []
        for child in children:
            slot = hash(child.to_bytes(size)) & mask
            while True:
                held = slots[slot]
                if not held:
                    number = len(states)
                    slots[slot] = number + 1
                    states.append(child)
                    layer.append(number)
                    if 2 * number + 2 > mask:
                        self._mask = mask = 2 * mask + 1
                        self._fill_slots()
                        slots = self._slots
                    break
                if states[held - 1] == child:
                    number = held - 1
                    break
                slot = (slot + 1) & mask
            numbers.append(number)
        return numbers

    def _fill_slots(self) -> None:
        """A table of `_mask` + 1 slots holding every state."""
        mask = self._mask
        self._slots = slots = array("i", bytes(4 * (mask + 1)))
        size = self._size
        for number, state in enumerate(self.states, start=1):
            slot = hash(state.to_bytes(size)) & mask
            while slots[slot]:
                slot = (slot + 1) & mask
            slots[slot] = number

    @property
    def stored(self) -> int:
        """Edges kept."""
        return len(self.targets)

    @property
    def closed(self) -> bool:
        """No state outside the neighbourhood is reachable from it."""
        return not self.frontier and not self.full

    def grow(self) -> None:
        """Add the states one step further from the trajectory."""
        self.depth += 1
        states = self.states
        layer: list[int] = []
        first, targets, kept = self.first, self.targets, self.actions
        number = self._number_children
        successors = self._successors if self._previous else self.space.generator.successors
        max_states, max_edges = self.max_states, EDGES_PER_STATE * self.max_states
        for state in self.frontier:
            self._tick()
            actions, children = successors(states[state])
            if len(states) + len(children) > max_states or len(targets) > max_edges:
                self.full = True
                self.frontier = []
                return
            targets.extend(number(children, layer))
            kept.extend(actions)
            first.append(len(targets))
        self.frontier = layer

    def _tick(self) -> None:
        self._ticks += 1
        if self._ticks % CHECK_EVERY == 0 and self.limits.passed():
            raise OutOfTime

    def cheapest(self, bound: tuple[float, int]) -> list[int] | None:
        """The cheapest plan through the neighbourhood's states, if better than `bound`."""
        if self.space.unit:
            return self._breadth_first(bound[1])
        return self._dijkstra(bound)

    def _breadth_first(self, steps: int) -> list[int] | None:
        states, first, actions, targets = self.states, self.first, self.actions, self.targets
        positive, negative = self.space.positive, self.space.negative  # the goal, inline
        expanded = len(first) - 1
        parents = array("l", [-1]) * len(states)  # -1: not reached; the start is 0
        via = array("i", [0]) * len(states)
        layer, length = [0], 0
        while layer and length + 1 < steps:
            length += 1
            following = []
            for number in layer:
                if number >= expanded:
                    continue
                self._tick()
                for edge in range(first[number], first[number + 1]):
                    child = targets[edge]
                    if child and parents[child] < 0:
                        parents[child], via[child] = number, actions[edge]
                        state = states[child]
                        if state & positive == positive and not state & negative:
                            return _path(parents, via, child)
                        following.append(child)
            layer = following
        return None

    def _dijkstra(self, bound: tuple[float, int]) -> list[int] | None:
        """Dijkstra by (cost, steps), written out: a (cost, steps) tuple built and
        compared per edge took a third of its time. A state not expanded that is not a
        goal is never queued: it would be popped and dropped, and most states are such
        (the last layer), so it is marked done when first met."""
        states, first, costs = self.states, self.first, self.space.costs
        positive, negative = self.space.positive, self.space.negative  # the goal, inline
        actions, targets, expanded = self.actions, self.targets, len(first) - 1
        count = len(states)
        bound_cost, bound_steps = bound
        best_cost = array("d", [bound_cost]) * count  # what a child must beat: the bound first
        best_steps = array("l", [bound_steps]) * count
        best_cost[0], best_steps[0] = 0.0, 0
        parents = array("l", [-1]) * count
        via = array("i", [0]) * count
        queue = [(0.0, 0, 0)]
        done = bytearray(count)
        pop, push = heapq.heappop, heapq.heappush
        while queue:
            cost, steps, number = pop(queue)
            if done[number]:
                continue
            done[number] = 1
            if cost > bound_cost or (cost == bound_cost and steps >= bound_steps):
                return None
            state = states[number]
            if state & positive == positive and not state & negative:
                return _path(parents, via, number)
            if number >= expanded:
                continue
            self._tick()
            steps += 1
            start, end = first[number], first[number + 1]
            for child, i in zip(targets[start:end], actions[start:end]):
                if done[child]:
                    continue
                if child >= expanded:  # a leaf: all it can be is a goal
                    leaf = states[child]
                    if not (leaf & positive == positive and not leaf & negative):
                        done[child] = 1
                        continue
                reached = cost + costs[i]
                held = best_cost[child]
                if reached < held or (reached == held and steps < best_steps[child]):
                    best_cost[child], best_steps[child] = reached, steps
                    parents[child], via[child] = number, i
                    push(queue, (reached, steps, child))
        return None


def _path(parents: array[int], via: array[int], number: int) -> list[int]:
    """The actions from the start (number 0) to `number`, by each state's parent."""
    steps: list[int] = []
    while number:
        steps.append(via[number])
        number = parents[number]
    steps.reverse()
    return steps
