"""Ctrl-C and SIGTERM stop the work at the next tick, so the run can be wrapped up.

A robot run that an operator stops is the one whose trace is needed. The first signal
only sets a flag that the acting loop reads between ticks: the tree is then halted (the
world's halting logic runs), the summary is printed and the outputs are closed. A second
signal exits at once, as a user pressing Ctrl-C twice expects; the trace survives
that too, because it is written line by line.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from types import FrameType, TracebackType

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, Self

if TYPE_CHECKING:
    import signal
else:
    try:  # CPython's own module beneath `signal`, which builds three enums on import
        import _signal as signal  # (1 ms of a 50 ms plan run) that is not needed here
    except ImportError:
        import signal

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupts:
    """While active, SIGINT and SIGTERM set `signum` instead of killing the process.

    Calling the object answers "should the work stop now?", which is the form the
    acting loop takes (`stop=`). Exit codes follow the shell's convention: 128 + signal.
    """

    def __init__(self) -> None:
        self.signum: int | None = None
        self._previous: dict[int, Any] = {}
        self._reading = False

    def __call__(self) -> bool:
        return self.signum is not None

    @property
    def exit_code(self) -> int:
        """128 plus the signal that came (130 for SIGINT, 143 for SIGTERM), as a shell reports a
        process killed by it; SIGINT's code when none came."""
        return 128 + (self.signum or signal.SIGINT)

    def __enter__(self) -> Self:
        for number in SIGNALS:
            try:
                if signal.getsignal(number) == signal.SIG_IGN:
                    continue  # ignored by whoever started us (a background job): stays so
                self._previous[number] = signal.signal(number, self._handle)
            except ValueError:  # not the main thread: leave signals alone
                break
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        for number, handler in self._previous.items():
            signal.signal(number, handler)
        self._previous.clear()

    @contextmanager
    def reading(self) -> Iterator[None]:
        """While inputs are read: a signal ends the reading at once (ReadInterrupted), also
        an `open()` blocked on a named pipe no one writes to, which Python would
        otherwise retry after the handler, for ever."""
        self._reading = True
        try:
            yield
        finally:
            self._reading = False

    def _handle(self, signum: int, frame: FrameType | None) -> None:
        if self.signum is not None:
            os._exit(128 + signum)
        self.signum = signum
        if self._reading:
            raise ReadInterrupted(signum)
        from signal import Signals

        name = "Ctrl-C" if signum == signal.SIGINT else Signals(signum).name
        message = (f"\n{name}: stopping after this tick (press Ctrl-C again to quit at once)\n")
        try:
            os.write(2, message.encode())
        except OSError:
            pass


class ReadInterrupted(BaseException):
    """A signal came while the inputs were read (Interrupts.reading)."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.exit_code = 128 + signum


class TimeLimitReached(BaseException):
    """The hard time limit of a command went off (a BaseException: no `except Exception`
    in the work may swallow it)."""


class HardDeadline:
    """A wall-clock limit that holds wherever the work is: in reading, grounding, search.

    The planner checks its own deadline between steps and stops cleanly, saying how far
    it got; some steps (grounding a wide problem, building the relaxed model) run long
    between two checks. So a timer (SIGALRM) also goes off `GRACE` seconds after the
    limit, raising TimeLimitReached wherever the work is. `phase` says what it was doing.
    """

    GRACE = 0.0

    def __init__(self, seconds: float | None, started: float, grace: float | None = None
                 ) -> None:
        """`started`: the time.monotonic() the limit counts from (the command's start);
        `grace`: seconds past the limit the timer waits (by default GRACE), for work
        that stops itself at the limit on its next check (a run, at the next tick)."""
        self.seconds = seconds
        self.started = started
        self.grace = self.GRACE if grace is None else grace
        self.phase = "reading the task"
        self._armed = False
        self.expire: Callable[[str], None] | None = None
        """Called with the phase when the timer goes off, before TimeLimitReached is
        raised: work with nothing to clean up may end the process there, instead of
        unwinding (and freeing) hundreds of megabytes of grounded model first."""

    def __enter__(self) -> Self:
        if self.seconds:
            try:
                self._previous = signal.signal(signal.SIGALRM, self._handle)
                left = max(0.01, self.started + self.seconds + self.grace
                           - time.monotonic())
                signal.setitimer(signal.ITIMER_REAL, left)
                self._armed = True
            except ValueError:  # not the main thread: the planner's own checks only
                pass
        return self

    def disarm(self) -> None:
        """The limited work is done (what follows, writing the outputs, is not cut)."""
        if self._armed:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, self._previous)
            self._armed = False

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.disarm()

    def _handle(self, signum: int, frame: FrameType | None) -> None:
        if self.expire is not None:
            self.expire(self.phase)
        raise TimeLimitReached


def process_start() -> float:
    """The time.monotonic() at which this process started (its interpreter's start-up
    included): the console script's limits count from there, as a user timing the
    command does."""
    return time.monotonic() - process_age()


def process_age() -> float:
    """Seconds since this process started. 0 where /proc is missing."""
    try:
        with open("/proc/self/stat", "rb") as handle:
            fields = handle.read().rsplit(b")", 1)[1].split()
        with open("/proc/uptime", "rb") as handle:
            uptime = float(handle.read().split()[0])
        return max(0.0, uptime - int(fields[19]) / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return 0.0
