"""A Groot2 server: BehaviorTree.CPP 4's monitoring protocol over ZeroMQ, for a tree
that grows.

Groot2 (and other monitors of BT.CPP) connect to a REP socket on PORT and a PUB socket
on PORT+1. Every request is a multipart message whose first part is a 6-byte header:
protocol (2), request type (an ASCII letter) and a request id (4 bytes, little endian).
Every reply starts with a 22-byte header: the request's header and the tree's 16-byte
UUID, followed by the payload:

- `T` FULLTREE: the tree's XML, with a `_uid` on every node (tree_state);
- `S` STATUS: 3 bytes per node, its uid and its status code;
- `B` BLACKBOARD: for the blackboard names in the second part (`;`-separated), the
  JSON object {name: {entry: value}} in MessagePack; btplan's one blackboard, named
  after the tree, holds the world's facts and the tick;
- `D` HOOKS_DUMP: `[]`; `A`, `X` (remove, disable every hook): nothing, there are none;
- `r` TOGGLE_RECORDING and `t` GET_TRANSITIONS: the status changes since recording
  started, 9 bytes each (6 of microseconds since the start, uid, status);
- breakpoints (`I`, `R`, `U`) and anything else: BT.CPP's error reply, the two parts
  `error` and a message.

Any request counts as the client's heartbeat; `connected` says whether one came within
HEARTBEAT seconds. The UUID changes whenever the tree grows, which tells a client to
fetch the tree again. The sockets are served from a thread of their own; the run's
thread only swaps in the new state after each tick.
"""

from __future__ import annotations

import struct
import threading
import time
from collections import deque

from btplan.errors import InputError
from btplan.monitor.tree_state import TreeState

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.monitor.run_monitor import TickUpdate

__all__ = ["DEFAULT_PORT", "HEARTBEAT", "Groot2Server"]

DEFAULT_PORT = 1667
"""Groot2's default port (BT.CPP's Groot2Publisher uses the same)."""

HEARTBEAT = 5.0
"""Seconds without a request after which the client counts as gone (BT.CPP: 5000 ms)."""

PROTOCOL = 2
REQUEST_HEADER = struct.Struct("<BBI")
TRANSITIONS_KEPT = 1000
"""Transitions kept while recording, the newest (BT.CPP keeps as many)."""


class Groot2Server:
    """Serves the latest state of a run's tree to Groot2 clients (module docstring)."""

    def __init__(self, port: int = DEFAULT_PORT, host: str = "127.0.0.1") -> None:
        import zmq

        self.port, self.host = port, host
        self._context = zmq.Context()
        self._server = self._context.socket(zmq.REP)
        self._publisher = self._context.socket(zmq.PUB)
        for socket in (self._server, self._publisher):
            socket.setsockopt(zmq.LINGER, 0)
        self._server.setsockopt(zmq.SNDTIMEO, 1000)
        try:
            self._server.bind(f"tcp://{host}:{port}")
            self._publisher.bind(f"tcp://{host}:{port + 1}")
        except zmq.ZMQError as error:
            self._context.destroy(linger=0)
            raise InputError(f"--groot {port}: cannot listen on {host}:{port} and "
                             f"{port + 1}: {error.strerror}",
                             hint="choose another port: --groot PORT") from None
        self._lock = threading.Lock()
        self._uuid = bytes(16)
        self._xml = b""
        self._status = b""
        self._board: dict[str, object] = {}
        self._name = "MainTree"
        self._recording_since: float | None = None
        self._transitions: deque[bytes] = deque(maxlen=TRANSITIONS_KEPT)
        self._last_request = float("-inf")
        self.requests = 0
        self._running = True
        self._thread = threading.Thread(target=self._serve, name="groot2", daemon=True)
        self._thread.start()

    # --- the run's side --------------------------------------------------------------------

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        """The tree after a tick: its XML (when it changed), statuses and blackboard."""
        board = {"facts": sorted(state.facts), "tick": state.tick}
        status = state.status_buffer()
        with self._lock:
            if state.uuid != self._uuid:
                self._uuid, self._xml = state.uuid, state.xml.encode()
            self._status, self._board, self._name = status, board, state.name
            if self._recording_since is not None:
                at = int((time.time() - self._recording_since) * 1e6)
                stamp = at.to_bytes(8, "little")[:6]
                self._transitions.extend(stamp + uid.to_bytes(2, "little") + bytes([code])
                                         for uid, code in update.transitions)

    @property
    def connected(self) -> bool:
        """Whether a client sent a request within the last HEARTBEAT seconds."""
        return time.monotonic() - self._last_request < HEARTBEAT

    def close(self) -> None:
        """Stop serving and free both ports."""
        self._running = False
        self._thread.join(timeout=2.0)
        self._context.destroy(linger=0)

    def __enter__(self) -> Groot2Server:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # --- the socket's side -----------------------------------------------------------------

    def _serve(self) -> None:
        import zmq

        poller = zmq.Poller()
        poller.register(self._server, zmq.POLLIN)
        while self._running:
            try:
                if not poller.poll(100):
                    continue
                parts = self._server.recv_multipart()
                self._last_request = time.monotonic()
                self.requests += 1
                self._server.send_multipart(self._reply(parts))
            except zmq.ZMQError:
                if not self._running:
                    return
                continue

    def _reply(self, parts: list[bytes]) -> list[bytes]:
        if not parts or len(parts[0]) != REQUEST_HEADER.size:
            return [b"error", b"wrong request header"]
        _, kind, request_id = REQUEST_HEADER.unpack(parts[0])
        with self._lock:
            header = REQUEST_HEADER.pack(PROTOCOL, kind, request_id) + self._uuid
            return self._answer(chr(kind), parts, header)

    def _answer(self, kind: str, parts: list[bytes], header: bytes) -> list[bytes]:
        if kind in "TSB" and not self._xml:
            return [b"error", b"the run has not made its first tick yet"]
        if kind == "T":
            return [header, self._xml]
        if kind == "S":
            return [header, self._status]
        if kind == "B":
            if len(parts) != 2:
                return [b"error", b"must be 2 parts message"]
            return [header, self._blackboard(parts[1].decode(errors="replace"))]
        if kind == "D":
            return [header, b"[]"]
        if kind in "AX":
            return [header]
        if kind == "r":
            return self._recording(parts, header)
        if kind == "t":
            transitions, self._transitions = b"".join(self._transitions), deque(
                maxlen=TRANSITIONS_KEPT)
            return [header, transitions]
        if kind in "IRU":
            return [b"error", b"btplan does not stop at breakpoints"]
        return [b"error", b"Request not recognized"]

    def _blackboard(self, names: str) -> bytes:
        import msgpack  # type: ignore[import-untyped]

        wanted = {name: self._board for name in names.split(";") if name == self._name}
        packed: bytes = msgpack.packb(wanted or None)
        return packed

    def _recording(self, parts: list[bytes], header: bytes) -> list[bytes]:
        if len(parts) != 2:
            return [b"error", b"must be 2 parts message"]
        command = parts[1]
        if command == b"start":
            self._recording_since = time.time()
            self._transitions.clear()
            return [header, str(int(self._recording_since * 1e6)).encode()]
        if command == b"stop":
            self._recording_since = None
        return [header]
