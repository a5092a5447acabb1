"""The monitors `btplan run` can open: Groot2's live protocol (`--groot [PORT]`), a
Groot2 replay file (`--btlog FILE.btlog`) and the browser view (`--view [PORT]`)."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

from btplan.cli import OPTIONAL_PORTS
from btplan.errors import InputError, Span

__all__ = ["closing_monitors", "open_monitors", "with_default_ports"]


def with_default_ports(argv: Sequence[str]) -> list[str]:
    """The command line with the default port put after a port option given without
    one (`--groot` alone, or followed by another option or an argument that is no
    port): typer has no option whose value may be left out."""
    out: list[str] = []
    for at, word in enumerate(argv):
        out.append(word)
        default = OPTIONAL_PORTS.get(word)
        if default is not None:
            following = argv[at + 1] if at + 1 < len(argv) else ""
            if not following.isdigit():
                out.append(default)
    return out


def check_port(flag: str, port: int | None) -> None:
    """A server's port is bad input unless it and the next one are ports."""
    if port is not None and not 1 <= port <= 65534:
        raise InputError(f"{flag} {port}: a port is a number from 1 to 65534 (the next one "
                         "is used too)", Span(flag, 1, 1))


def check_btlog(path: str | None) -> None:
    """A replay file's name must end in .btlog (Groot2 opens them by the suffix)."""
    if path is not None and not path.endswith(".btlog"):
        raise InputError(f"--btlog {path}: the file name must end in .btlog",
                         Span("--btlog", 1, 1), "Groot2 opens replay files by that suffix")


def open_monitors(groot: int | None, btlog: str | None, view: int | None, world: Any,
                  title: str, more: Sequence[Any] = ()) -> Any:
    """The run's monitor (a tick view that also makes the trace's lines), with the
    Groot2 server, the replay file and the browser view when asked for, and `more`
    (a ROS 2 robot's tree topics)."""
    from btplan.monitor.run_monitor import Monitor, RunMonitor

    monitors: list[Monitor] = []
    if view is not None:
        from btplan.cli.typer_app import stderr
        from btplan.monitor.browser import LIVE_LINES, BrowserView, TraceLines

        from btplan.robot.contract import capabilities_of

        camera = world.camera_png if capabilities_of(world).camera else None
        browser = BrowserView(TraceLines(keep=LIVE_LINES), title, view, camera=camera)
        monitors.append(browser)
        stderr.print(f"btplan run: the view is at {browser.url}")
    if groot is not None:  # first: the one that can fail (a port in use)
        from btplan.monitor.groot2 import Groot2Server

        monitors.append(Groot2Server(groot))
    if btlog is not None:
        from btplan.monitor.btlog import BtlogWriter

        monitors.append(BtlogWriter(btlog))
    monitors.extend(more)
    facts = sorted(str(atom) for atom in world.facts())
    return RunMonitor(monitors, "MainTree", facts)


@contextmanager
def closing_monitors(monitor: Any) -> Iterator[None]:
    """Close the run's monitors when the run ends, however it ends: the replay file is
    written then, and the Groot2 port is freed."""
    try:
        yield
    finally:
        monitor.close()
