"""The `btplan view` command: a saved run's trace, drawn tick by tick in the browser."""

from __future__ import annotations

import json
import time
from typing import Annotated

import typer

from btplan.cli.console import escape
from btplan.cli.interrupts import Interrupts
from btplan.cli.typer_app import app, guarded, stderr
from btplan.errors import InputError, Span

EXAMPLES = """Examples:

  btplan run domains/pick_place_obstacle.bt --scenario examples/example2.dist --trace run.jsonl -q
  btplan view run.jsonl
  btplan view run.jsonl --port 0 --open
"""

MAX_TRACE_BYTES = 1 << 30
"""Largest trace read (1 GiB): the page holds every line in the browser's memory."""


@app.command(epilog=EXAMPLES)
@guarded
def view(
    trace: Annotated[str, typer.Argument(
        metavar="TRACE.jsonl", help="A trace written by `btplan run --trace`.")],
    port: Annotated[int, typer.Option(
        "--port", min=0, max=65535, metavar="PORT",
        help="Port on 127.0.0.1 to serve the page on (0: a free one).")] = 8765,
    open_browser: Annotated[bool, typer.Option(
        "--open", help="Open the page in the system's browser.")] = False,
) -> None:
    """Serve a run's trace as a page: the tree in the paper's notation, coloured by status,
    the nodes each growth added, and a timeline to scrub tick by tick with the facts,
    the actions and the disturbances of each tick. Runs until Ctrl-C.
    """
    from btplan.monitor.browser import BrowserView, TraceLines

    lines = read_trace(trace)
    server = BrowserView(TraceLines(lines), trace, port, live=False)
    stderr.print(f"btplan view: {len(lines)} ticks of {escape(trace)} at {server.url} "
                 "(Ctrl-C to stop)")
    if open_browser:
        import webbrowser

        webbrowser.open(server.url)
    with Interrupts() as interrupted:
        while not interrupted():
            time.sleep(0.1)
    server.close()


def read_trace(path: str) -> list[str]:
    """The trace's lines, each checked to be a tick's JSON object; the first must hold the
    tree (a trace of `btplan run --trace`)."""
    lines: list[str] = []
    try:
        with open(path, encoding="utf-8") as stream:
            read = 0
            for number, raw in enumerate(stream, 1):
                read += len(raw)
                if read > MAX_TRACE_BYTES:
                    raise InputError(f"the trace is larger than {MAX_TRACE_BYTES >> 30} GiB",
                                     Span(path, number, 1))
                if raw.strip():
                    lines.append(_checked(raw.strip(), path, number, first=not lines))
    except FileNotFoundError:
        raise InputError("no such file", Span(path, 1, 1)) from None
    except IsADirectoryError:
        raise InputError("is a directory, not a file", Span(path, 1, 1)) from None
    except UnicodeDecodeError as error:
        raise InputError(f"not UTF-8 text ({error.reason})", Span(path, 1, 1)) from None
    if not lines:
        raise InputError("the trace is empty", Span(path, 1, 1),
                         "write one with: btplan run DOMAIN --trace FILE")
    return lines


def _checked(line: str, path: str, number: int, first: bool) -> str:
    try:
        tick = json.loads(line)
    except json.JSONDecodeError as error:
        raise InputError(f"not a JSON line: {error.msg}", Span(path, number, error.colno),
                         "a trace has one JSON object per tick") from None
    if not isinstance(tick, dict) or "tick" not in tick:
        raise InputError("not a tick of a trace (no \"tick\")", Span(path, number, 1))
    if first and "tree" not in tick:
        raise InputError("this trace does not hold the tree", Span(path, number, 1),
                         "traces of `btplan run --trace` hold it from this version on; "
                         "record the run again")
    return line
