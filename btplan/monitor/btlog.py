"""A run written as BehaviorTree.CPP's FileLogger2 file (`.btlog`), which Groot2 replays.

The layout, as FileLogger2 writes it: the text `BTCPP4-FileLogger2`, a protocol byte
(1), the length of the tree's XML (4 bytes, little endian) and the XML (every node
with its `_uid`), the time the log started (8 bytes, microseconds since the epoch),
then one transition per 9 bytes: 6 bytes of microseconds since the start, the node's
uid (2 bytes) and its new status (0 idle, 1 running, 2 success, 3 failure, 4 skipped).

The file starts with the tree, and btplan's tree grows while the run goes on: the XML
written is the final tree, and a node grown later simply has no transition before it
appears, so Groot2 shows it idle until then. The transitions are kept in a spool file
while the run goes on; the log is put together when the run ends, however it ends
(the goal, a limit, Ctrl-C, SIGTERM), all at once beside the target and renamed over
it, so that no half-written log is ever left.
"""

from __future__ import annotations

import struct
import tempfile
import time
from collections.abc import Iterator

from btplan.io import write_chunks_atomic
from btplan.monitor.tree_state import TreeState

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.monitor.run_monitor import TickUpdate

__all__ = ["MAGIC", "BtlogWriter", "read_btlog"]

MAGIC = b"BTCPP4-FileLogger2"
PROTOCOL = 1
TRANSITION = struct.Struct("<HB")
CHUNK = 1 << 20


class BtlogWriter:
    """Collects a run's transitions and writes the `.btlog` file when closed."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.started = time.time()
        self._spool = tempfile.TemporaryFile()
        self._state: TreeState | None = None
        self.transitions = 0

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        """One tick's transitions, stamped with the time they are taken in."""
        self._state = state
        transitions = update.transitions
        if not transitions:
            return
        stamp = int((time.time() - self.started) * 1e6).to_bytes(8, "little")[:6]
        self._spool.write(b"".join(stamp + TRANSITION.pack(uid, status)
                                   for uid, status in transitions))
        self.transitions += len(transitions)

    def close(self) -> None:
        """Write the log (the final tree, then every transition) and drop the spool."""
        try:
            xml = (self._state.xml if self._state is not None else "").encode()
            head = (MAGIC + bytes([PROTOCOL]) + struct.pack("<i", len(xml)) + xml
                    + struct.pack("<q", int(self.started * 1e6)))
            write_chunks_atomic(self.path, self._chunks(head))
        finally:
            self._spool.close()

    def _chunks(self, head: bytes) -> Iterator[bytes]:
        yield head
        self._spool.seek(0)
        while chunk := self._spool.read(CHUNK):
            yield chunk


def read_btlog(data: bytes) -> tuple[str, int, list[tuple[int, int, int]]]:
    """The XML, the start time (microseconds since the epoch) and the transitions
    (microseconds since the start, uid, status) of a FileLogger2 file."""
    if not data.startswith(MAGIC) or len(data) < len(MAGIC) + 5:
        raise ValueError("not a FileLogger2 file (no BTCPP4-FileLogger2 header)")
    at = len(MAGIC) + 1
    (size,) = struct.unpack_from("<i", data, at)
    at += 4
    xml = data[at:at + size].decode()
    at += size
    (started,) = struct.unpack_from("<q", data, at)
    at += 8
    out = []
    while at + 9 <= len(data):
        stamp = int.from_bytes(data[at:at + 6], "little")
        uid, status = TRANSITION.unpack_from(data, at + 6)
        out.append((stamp, uid, status))
        at += 9
    return xml, started, out
