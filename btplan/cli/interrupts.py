"""Ctrl-C and SIGTERM stop the work at the next tick, so the run can be wrapped up.

A robot run that an operator stops is the one whose trace is needed. The first signal
only sets a flag that the acting loop reads between ticks: the tree is then halted (the
world's halting logic runs), the summary is printed and the outputs are closed. A second
signal exits at once, as a user pressing Ctrl-C twice expects; the trace survives
that too, because it is written line by line.
"""

from __future__ import annotations

import os
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

    def __call__(self) -> bool:
        return self.signum is not None

    @property
    def exit_code(self) -> int:
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

    def _handle(self, signum: int, frame: FrameType | None) -> None:
        if self.signum is not None:
            os._exit(128 + signum)
        self.signum = signum
        from signal import Signals

        name = "Ctrl-C" if signum == signal.SIGINT else Signals(signum).name
        message = (f"\n{name}: stopping after this tick (press Ctrl-C again to quit at once)\n")
        try:
            os.write(2, message.encode())
        except OSError:
            pass
