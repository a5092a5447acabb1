"""The last resort for the whole task: a plan for the whole goal, searched for from the
initial state, for btplan/acting/offline/planning.py to put behind the goal tree.

The search is begun once and resumed: offline planning gives it a slice of the time
as soon as backchaining's first attempt has failed (backchaining is visibly stuck, and
retries and later strategies rarely do better), and whatever is left once every
strategy has failed. h^2 is asked first whether the goal can hold at all.
"""

from __future__ import annotations

import time

from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex
from btplan.worlds.symbolic import SymbolicWorld

TYPE_CHECKING = False
if TYPE_CHECKING:  # the search is loaded only when a plan run needs it
    from btplan.planner.search import Portfolio, SearchRun

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
    """The whole-goal search's early slice, taken once, when the first attempt fails."""

    def __init__(self, last: WholeGoalSearch, deadline: float) -> None:
        self.last, self.deadline = last, deadline
        self.taken = False

    def take(self) -> list[GroundAction] | None:
        """Search for EARLY_SHARE of the time left (once); the plan, if one is found."""
        if self.taken:
            return None
        self.taken = True
        now = time.perf_counter()
        return self.last.resume(now + (self.deadline - now) * EARLY_SHARE)


class SearchTurns:
    """Turns of the whole-goal search while backchaining's attempts still run.

    On a large model one attempt of backchaining can use most of its share of the time
    limit before it fails (parking: 17-24 s of 30), and the search, which needs some
    ten seconds there, is left too little. So once backchaining has run
    FIRST_TURN_SHARE of the time limit, the search gets a turn as long as backchaining
    has had since the last turn, and so on: past that first wait, each gets about half
    of the time until `until` (backchaining's share). The search resumes where its last
    turn stopped, so no turn is lost. The first wait grows with the limit: where
    backchaining makes steady progress (200 blocks: 486 expansions in about a minute), an early
    turn halves its speed and lets the search's stored states grow to a gigabyte.
    """

    def __init__(self, last: WholeGoalSearch, started: float, limit: float, until: float) -> None:
        self.last, self.until = last, until
        self.since = started
        """When backchaining last got the time back."""
        self.next_turn = started + FIRST_TURN_SHARE * limit
        self.turns = 0

    def take(self) -> list[GroundAction] | None:
        """The plan, when a turn is due now and the search finds one in it."""
        now = time.perf_counter()
        if (now < self.next_turn or now >= self.until or self.last.proof is not None
                or self.last.too_wide):
            return None
        self.turns += 1
        steps = self.last.resume(min(now + max(now - self.since, MIN_TURN), self.until))
        self.since = time.perf_counter()
        self.next_turn = self.since + (self.since - now)  # as long again for backchaining
        return steps


FIRST_TURN_SHARE = 0.25
"""The share of the time limit backchaining has before the search's first turn."""

MIN_TURN = 0.5
"""The shortest turn: the search's first states set up its heuristics."""


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
    except (OSError, AttributeError):  # not glibc: the memory stays for reuse
        pass
