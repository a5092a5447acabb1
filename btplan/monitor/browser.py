"""The browser view: a run's tree, tick by tick, in a page served on 127.0.0.1.

`btplan view TRACE.jsonl` serves a saved trace; `btplan run --view [PORT]` serves the
run as it goes (a Monitor of btplan.monitor.run_monitor). The page (btplan/monitor/web)
asks for the trace's lines with `GET /lines?from=N` and draws them itself: nothing to
install and nothing fetched from the internet.

- `GET /` the page, `/view.js`, `/view.css` its parts;
- `GET /info`: `{"title", "live", "done", "lines"}`;
- `GET /frame?tick=T`: the camera's last picture at or before tick T (PNG), in a world
  that has a camera (the PyBullet worlds); at most one every FRAME_GAP seconds;
- `GET /lines?from=N`: the trace lines from the N-th on (JSON lines). A live run keeps
  its last LIVE_LINES lines; asked for older ones, it answers first with a `base` line
  holding the tree and the facts where the kept lines start.
"""

from __future__ import annotations

import json
import threading
import time
from collections import OrderedDict, deque
from collections.abc import Callable
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from typing import Any
from urllib.parse import parse_qs, urlparse

from btplan.errors import InputError
from btplan.monitor.tree_state import TreeState

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.monitor.run_monitor import TickUpdate

__all__ = ["DEFAULT_PORT", "LIVE_LINES", "BrowserView", "TraceLines"]

DEFAULT_PORT = 8765
CLOSE_WAIT = 2.0
"""Seconds a run's end waits for a watching page to fetch its last ticks."""

FRAMES_KEPT = 1000
"""Camera pictures a live view keeps (the last ones; about 60 kB each)."""

FRAME_GAP = 0.25
"""Seconds between two pictures at least: a picture takes tens of milliseconds to
render, more than a tick of a run at full speed."""

LIVE_LINES = 50_000
"""Ticks a live view keeps for scrubbing back; older ones are folded into a base line."""

ASSETS = {"/": ("view.html", "text/html; charset=utf-8"),
          "/view.js": ("view.js", "text/javascript; charset=utf-8"),
          "/view.css": ("view.css", "text/css; charset=utf-8")}


class TraceLines:
    """The trace lines a view serves: all of a saved trace, or the last `keep` of a run."""

    def __init__(self, lines: list[str] | None = None, keep: int | None = None) -> None:
        self._lines: deque[str] = deque(lines or [], maxlen=keep)
        self._first = 0
        """Index (in the whole run) of the first line kept."""
        self._base: dict[str, Any] | None = None
        self._facts: set[str] = set()
        self.lock = threading.Lock()
        self.done = lines is not None

    def append(self, line: str) -> None:
        """A run's new tick; past `keep`, the oldest is folded into the base line."""
        with self.lock:
            if self._lines.maxlen is not None and len(self._lines) == self._lines.maxlen:
                self._fold(json.loads(self._lines[0]))
                self._first += 1
            self._lines.append(line)

    def _fold(self, dropped: dict[str, Any]) -> None:
        """Keep what the dropped line meant for the ones after it: the tree, the facts."""
        base = self._base or {"base": True, "tree": [], "facts_at_start": []}
        if "facts_at_start" in dropped:
            self._facts = set(dropped["facts_at_start"])
        self._facts.difference_update(dropped["facts"]["removed"])
        self._facts.update(dropped["facts"]["added"])
        if "tree" in dropped:
            base["tree"] = dropped["tree"]
        base["facts_at_start"] = sorted(self._facts)
        base["tick"] = dropped["tick"]
        self._base = base

    @property
    def total(self) -> int:
        """Lines of the run so far, those folded into the base line included."""
        with self.lock:
            return self._first + len(self._lines)

    def since(self, start: int) -> tuple[list[str], int]:
        """The lines from index `start` on, and the total so far."""
        with self.lock:
            total = self._first + len(self._lines)
            if start >= total:
                return [], total
            if start < self._first:
                head = [json.dumps(self._base)] if self._base is not None else []
                return head + list(self._lines), total
            return list(self._lines)[start - self._first:], total


class BrowserView:
    """Serves the page and `lines` on host:port from a thread of its own."""

    def __init__(self, lines: TraceLines, title: str, port: int = DEFAULT_PORT,
                 host: str = "127.0.0.1", live: bool = True,
                 camera: Callable[[], bytes] | None = None) -> None:
        self.lines, self.title, self.live = lines, title, live
        self.camera = camera
        """Takes a PNG picture of the world after each tick (a world with a camera)."""
        self._frames: OrderedDict[int, bytes] = OrderedDict()
        self._pictured = float("-inf")
        self.served = 0
        """Lines a page has fetched (0: no page has come yet)."""
        self._told_done = False
        handler = type("Handler", (_Handler,), {"view": self})
        try:
            self._server = ThreadingHTTPServer((host, port), handler)
        except OSError as error:
            raise InputError(f"cannot serve the view on {host}:{port}: "
                             f"{error.strerror or error}",
                             hint="choose another port (0 picks a free one)") from None
        self._server.daemon_threads = True
        self.host, self.port = host, int(self._server.server_address[1])
        self._thread = threading.Thread(target=self._server.serve_forever,
                                        name="browser-view", daemon=True)
        self._thread.start()

    @property
    def url(self) -> str:
        """Where the page is (the port is the one given, or the free one picked for 0)."""
        return f"http://{self.host}:{self.port}/"

    # --- as a run's monitor ---------------------------------------------------------------

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        """Keep the tick's trace line (and the camera's picture, at most every FRAME_GAP)."""
        self.lines.append(update.line)
        now = time.monotonic()
        if self.camera is not None and now - self._pictured >= FRAME_GAP:
            self._pictured = now
            picture = self.camera()
            with self.lines.lock:
                self._frames[update.record.tick] = picture
                while len(self._frames) > FRAMES_KEPT:
                    self._frames.popitem(last=False)

    def frame(self, tick: int) -> bytes | None:
        """The last picture taken at or before `tick`, if it is still kept."""
        with self.lines.lock:
            taken = [t for t in self._frames if t <= tick]
            return self._frames[taken[-1]] if taken else None

    def close(self) -> None:
        """The run ended: a page that is watching gets the last ticks (and that the run is
        done) first, within CLOSE_WAIT seconds; then the server stops. The page keeps
        every tick it has, to scrub through after."""
        self.lines.done = True
        total = self.lines.total
        waited = time.monotonic() + CLOSE_WAIT
        while self.served and (self.served < total or not self._told_done) and (
                time.monotonic() < waited):
            time.sleep(0.02)
        self._server.shutdown()
        self._server.server_close()

    def info(self) -> dict[str, Any]:
        """What the page asks first and while it follows a run: the title, whether the
        run is live and done, how many lines there are, whether pictures come too."""
        total = self.lines.total
        self._told_done = self.lines.done and self.served >= total
        return {"title": self.title, "live": self.live, "done": self.lines.done,
                "lines": total, "frames": self.camera is not None}


class _Handler(BaseHTTPRequestHandler):
    view: BrowserView

    def do_GET(self) -> None:  # noqa: N802 (the name http.server calls)
        url = urlparse(self.path)
        if url.path in ASSETS:
            name, kind = ASSETS[url.path]
            self._send(resources.files("btplan.monitor.web").joinpath(name).read_bytes(), kind)
        elif url.path == "/info":
            self._send(json.dumps(self.view.info()).encode(), "application/json")
        elif url.path == "/frame":
            try:
                picture = self.view.frame(int(parse_qs(url.query).get("tick", ["-1"])[0]))
            except ValueError:
                picture = None
            if picture is None:
                self.send_error(HTTPStatus.NOT_FOUND)
            else:
                self._send(picture, "image/png")
        elif url.path == "/lines":
            try:
                start = int(parse_qs(url.query).get("from", ["0"])[0])
            except ValueError:
                start = 0
            lines, total = self.view.lines.since(max(0, start))
            self.view.served = max(self.view.served, total)
            body = "".join(line + "\n" for line in lines).encode()
            self._send(body, "application/x-ndjson", {"X-Lines": str(total)})
        else:
            self.send_error(HTTPStatus.NOT_FOUND)

    def _send(self, body: bytes, kind: str, headers: dict[str, str] | None = None) -> None:
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        for key, value in (headers or {}).items():
            self.send_header(key, value)
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002
        pass  # a view serves quietly; the run's own output stays readable
