"""What a robot's action returns, made into one running-skill handle the loop can poll.

In the style of BehaviorTree.CPP's StatefulActionNode and py_trees' behaviours, an
action of a `btplan.robot.Robot` starts a skill and the loop polls it once per tick,
never waiting for it. The action's function may return:

- a `Skill`: any object with `poll()` (and optionally `cancel()` and `stopped()`);
- a `concurrent.futures.Future`: running until done; its exception is the failure;
- a status or a bool (or None, for success): the action ended at once.

`threaded=True` actions run their function in a thread of their own, with a
`threading.Event` named `stop` that a halt sets: the usual shape of a driver call
that blocks until the motion is done.
"""

from __future__ import annotations

import threading
from concurrent.futures import Future, ThreadPoolExecutor

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

__all__ = ["Skill", "Running", "as_status"]


class Skill(Protocol):
    """A skill in progress: polled every tick, cancelled when the tree turns away.

    `poll()` answers RUNNING (or None) while it runs, then SUCCESS or FAILURE (or a
    bool); it must not block. An exception from it is the action's failure, with its
    message in the trace. `cancel()` asks it to stop; `stopped()` says whether it has
    (both optional: a skill without them stops at once)."""

    def poll(self) -> Status | bool | None:
        """RUNNING (or None) while it runs, then SUCCESS or FAILURE (or a bool)."""


def as_status(answer: object, what: str) -> Status:
    """A skill's answer as a status: None is RUNNING while polling."""
    if answer is None or answer is RUNNING:
        return RUNNING
    if answer is True or answer is SUCCESS:
        return SUCCESS
    if answer is False or answer is FAILURE:
        return FAILURE
    raise TypeError(f"{what} answered {answer!r}; expected RUNNING, SUCCESS, FAILURE or a bool")


class Running:
    """One started skill, whatever its kind, behind poll / cancel / stopped."""

    def __init__(self, what: str, skill: object, stop: threading.Event | None = None) -> None:
        self.what = what
        self.skill = skill
        self.stop = stop
        self.cancelled = False

    def poll(self) -> Status:
        """The skill's status now, whatever kind it is (a cancelled one has failed)."""
        skill = self.skill
        if isinstance(skill, Future):
            if not skill.done():
                return RUNNING
            error = skill.exception()
            if error is not None:
                raise error
            result = skill.result()
            if result is RUNNING:  # done, yet still running: a mistake, not a wait
                raise TypeError(f"{self.what} ended with RUNNING; a finished skill "
                                "answers SUCCESS, FAILURE, a bool or None")
            return SUCCESS if result is None else as_status(result, self.what)
        poll = getattr(skill, "poll", None)
        if not callable(poll):
            raise TypeError(f"{self.what} returned {skill!r}: not a skill (no poll method), "
                            "a Future, a status or a bool")
        return as_status(poll(), self.what)

    def cancel(self) -> None:
        """Ask the skill to stop: its `cancel()`, a future's cancel, a thread's event."""
        self.cancelled = True
        if self.stop is not None:
            self.stop.set()
        skill = self.skill
        if isinstance(skill, Future):
            skill.cancel()
            return
        cancel = getattr(skill, "cancel", None)
        if callable(cancel):
            cancel()

    def stopped(self) -> bool:
        """Whether a cancelled skill has come to rest (at once for one that cannot say)."""
        skill = self.skill
        if isinstance(skill, Future):
            return skill.done()
        stopped = getattr(skill, "stopped", None)
        return bool(stopped()) if callable(stopped) else True


class Threads:
    """The threads that threaded actions run in, made on first use."""

    def __init__(self) -> None:
        self._pool: ThreadPoolExecutor | None = None

    def submit(self, function: object, *args: object, stop: threading.Event) -> Future[object]:
        """Run a threaded action's function in a worker, with the event a halt sets."""
        if self._pool is None:
            self._pool = ThreadPoolExecutor(max_workers=8, thread_name_prefix="btplan-skill")
        return self._pool.submit(function, *args, stop=stop)  # type: ignore[arg-type]

    def shutdown(self) -> None:
        """Let the workers go; skills still running are cancelled."""
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None
