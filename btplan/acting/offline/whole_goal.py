"""The last resort for the whole task: a plan for the whole goal, searched for from the
initial state, for btplan/acting/offline/planning.py to put behind the goal tree.

The search is begun once and resumed: offline planning gives it a slice of the time
as soon as backchaining's first attempt has failed (backchaining is visibly stuck, and
retries and later strategies rarely do better), and whatever is left once every
strategy has failed. h^2 is asked first whether the goal can hold at all.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex
from btplan.worlds.symbolic import SymbolicWorld

TYPE_CHECKING = False
if TYPE_CHECKING:  # the search is loaded only when a plan run needs it
    from btplan.classical import Portfolio, SearchRun

WHOLE_STATES = 1_000_000
"""States the whole-goal search may expand; the time limit usually comes first."""

STORED_BYTES = 256 << 20
"""About the most memory the search's kept states and waiting children may take. A
state is a packed int of one bit per atom: with ten thousand balls in gripper, 5 kB a
state and 20,000 successors each, the search gives up before it takes gigabytes (and
backchaining goes on alone), as a planner that needs only the problem's size should."""

EARLY_SHARE = 0.5
"""The share of the time left that the search gets in its early slice."""


class WholeGoalSearch:
    """The whole-goal search of one planning call, begun when first needed."""

    def __init__(self, task: Task, models: AchieverIndex, seed: int) -> None:
        self.task, self.models, self.seed = task, models, seed
        self.proof: str | None = None
        """Why no plan exists, when h^2 proves it (then nothing is searched)."""
        self._run: SearchRun | Portfolio | None = None
        self._checked = False
        self.too_wide = ""
        """Why the search is left out on this problem (its groundings would not fit)."""

    def resume(self, until: float | None) -> list[GroundAction] | None:
        """Search on until a plan is found (returned), the search is over, or `until`."""
        if not self._checked:
            self._checked = True
            self.proof = unsolvable(self.task, self.models)
            if not self.models.fits_search():
                self.too_wide = (f"too wide to search whole ({len(self.models.relaxed.actions)} "
                                 f"groundings as bit masks would take about "
                                 f"{self.models.packed_bytes >> 20} MB)")
        if self.proof is not None or self.too_wide:
            return None
        if self._run is None:
            start = SymbolicWorld(self.task, seed=self.seed).facts()
            engine = self.models.subgoal_search
            self._run = engine.begin(
                start, list(self.task.goal_literals), max_states=WHOLE_STATES,
                max_bytes=STORED_BYTES, portfolio=True)
        if self._run.done:
            return self._run.plan
        steps = self._run.resume(until)
        if self._run.done:
            self.release()  # a plan or no plan: its states are not needed again
        return steps

    def release(self) -> None:
        """Drop the search's states and entries; it is over (planning has its tree)."""
        if self._run is not None and self._run.stored:
            self._run.release()
            give_back()

    def why(self, deadline: float | None) -> str:
        """Why no plan was found, and after how many states."""
        run = self._run
        if self.too_wide:
            return self.too_wide
        if run is None:
            return "not begun"
        reason = ("no plan exists" if run.exhausted
                  else "time limit reached" if not run.done and deadline is not None
                  and time.perf_counter() > deadline
                  else "bound of stored or expanded states reached" if run.done
                  else "stopped")
        return f"{reason} after {run.expanded} states"


class EarlySlice:
    """The whole-goal search's early slice, taken once, when the first attempt fails.

    An attempt that failed without ever holding more goals at once than at its start
    is visibly stuck: the search gets EARLY_SHARE of the time left (parking p04's first
    attempt fails within 1.4 s holding none of its 24 goals, and the search needs 12 s).
    One that got somewhere gets, within that, as long as backchaining would need for
    every goal at the pace it showed (`SearchTurns.pace`): a retry without the choice
    that failed may finish at that pace. 120 blocks: the first attempt held 14 of 69
    goals 1.2 s after its first tick when it failed, and the search then took 75 s
    (and 95 MB for its model) for a plan the retry finds in 4; now the slice is 6 s.
    """

    def __init__(self, last: WholeGoalSearch, deadline: float,
                 turns: SearchTurns | None = None) -> None:
        self.last, self.deadline, self.turns = last, deadline, turns
        self.taken = False

    def take(self) -> list[GroundAction] | None:
        """Search for the slice (once); the plan, if one is found."""
        if self.taken:
            return None
        self.taken = True
        now = time.perf_counter()
        share = (self.deadline - now) * EARLY_SHARE
        turns = self.turns
        if turns is not None:
            share = min(share, max(turns.pace(now), MIN_TURN))
        steps = self.last.resume(now + share)
        if turns is not None:
            turns.resumed()
        return steps


class SearchTurns:
    """Turns of the whole-goal search while backchaining's attempts still run, each
    earned by a stall of backchaining.

    On a large model one attempt of backchaining can run most of its share of the time
    limit and fail (parking once took 17-24 s of 30), leaving the search, which needs
    some seconds, too little. But where backchaining makes steady progress, a turn
    only slows it down, and the search's states take memory. So a turn is earned:
    backchaining's headway is the most goals an attempt has held at once (asked after
    every tick, LOOK_EVERY apart; a move that starts the world over, or a retry, must
    hold more than the best before to count), and it has stalled when it has not raised
    that for STALL_SHARE of the time planning has run (MIN_STALL at least). Then, once
    FIRST_TURN_SHARE of the limit has passed, the search gets a turn as long as the
    stall, resuming where its last turn stopped; backchaining gets the time back after
    it, and must stall as long again for the next. 200 blocks raise their best at
    least every 2.3 s over the 25 s they take.
    """

    def __init__(self, last: WholeGoalSearch, started: float, limit: float, until: float) -> None:
        self.last, self.started, self.until = last, started, until
        self.first = started + FIRST_TURN_SHARE * limit
        """No turn before this (`time.perf_counter()` value)."""
        self.since = started
        """When backchaining last raised its headway or got the time back from the
        search."""
        self.best = 0
        """The most goals an attempt has held at once."""
        self.source: Callable[[], int] | None = None
        """The current attempt's count of goals held (a new one: a new attempt)."""
        self.looked = started
        """When the current attempt was first looked at (after its first tick)."""
        self.start = self.reached = 0
        """The goals the current attempt held when first looked at, and at best since."""
        self.next_look = started
        self.turns = 0

    def take(self, headway: Callable[[], int] | None = None) -> list[GroundAction] | None:
        """The plan, when a turn is due now and the search finds one in it. `headway`
        counts the goals the current attempt holds now (the same callable throughout
        an attempt)."""
        now = time.perf_counter()
        if now < self.next_look:
            return None
        self.next_look = now + LOOK_EVERY
        if headway is not None:
            self._look(headway, now)
        if (now < self.first or now >= self.until or self.last.proof is not None
                or self.last.too_wide):
            return None
        stalled = self.stalled(now)
        if stalled < self.patience(now):
            return None  # backchaining is getting somewhere: it keeps the time
        self.turns += 1
        steps = self.last.resume(min(now + max(stalled, MIN_TURN), self.until))
        self.resumed()
        return steps

    def _look(self, headway: Callable[[], int], now: float) -> None:
        held = headway()
        if headway is not self.source:  # a new attempt, judged from its own start
            self.source, self.looked, self.start, self.reached = headway, now, held, held
            if not self.best:
                self.best = held
        self.reached = max(self.reached, held)
        if held > self.best:
            self.best, self.since = held, now

    def pace(self, now: float) -> float:
        """Seconds the current attempt would need for every goal at the pace it has
        raised the goals it holds; infinite when it has raised none."""
        gained = self.reached - self.start
        if gained <= 0:
            return math.inf
        return (now - self.looked) * len(self.last.task.goal_literals) / gained

    def stalled(self, now: float) -> float:
        """Seconds backchaining has run since it last raised its headway (or got the
        time back from the search)."""
        return now - self.since

    def patience(self, now: float) -> float:
        """How long backchaining may go without raising its headway before it has
        stalled: STALL_SHARE of the time planning has run, MIN_STALL at least."""
        return max(MIN_STALL, STALL_SHARE * (now - self.started))

    def resumed(self) -> None:
        """Backchaining has the time again: its stall is counted from now."""
        self.since = time.perf_counter()


FIRST_TURN_SHARE = 0.25
"""The share of the time limit backchaining has before the search's first turn."""

STALL_SHARE = 0.25
"""Backchaining has stalled when its headway has not risen for this share of the time
planning has run..."""

MIN_STALL = 2.0
"""...and for at least this many seconds."""

MIN_TURN = 0.5
"""The shortest turn: the search's first states set up its heuristics."""

LOOK_EVERY = 0.05
"""Seconds between two looks at backchaining's headway (a count over the goals)."""


def unsolvable(task: Task, models: AchieverIndex) -> str | None:
    """Why the goal can never hold, when h^2 proves it (the search would be in vain)."""
    goals = [g for g in task.goal_literals if g.positive]
    for goal in goals:
        if models.mutexes.unreachable(goal.atom):
            return f"{goal} can never hold (h^2 mutexes)"
    for i, first in enumerate(goals):
        for second in goals[i + 1:]:
            if models.mutexes.exclusive(first, second):
                return f"{first} and {second} can never hold together (h^2 mutexes)"
    return None


def give_back() -> None:
    """Hand the memory freed back to the system, where the C library can (glibc's
    malloc_trim): the search's queues are arrays the allocator keeps for reuse, and
    plan improvement, which comes next, takes its memory in small objects that cannot
    reuse it. Zenotravel p03: 39 MB resident after the search's release, 34 after this."""
    try:
        import ctypes

        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError, TypeError):  # not glibc: the memory stays for reuse
        pass
