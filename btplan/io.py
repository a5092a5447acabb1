"""Reading inputs and writing outputs the way every command does it.

Output files are written to a temporary file in the same folder and then renamed over
the target, so a crash or a bad input never leaves half a file behind.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from btplan.errors import InputError, Span
from btplan.limits import MAX_INPUT_BYTES, check_size

STDIO = "-"


def read_text(path: str) -> str:
    """Read a UTF-8 text file, or standard input for `-`, with errors a user can act on.

    At most MAX_INPUT_BYTES are read (btplan/limits.py).
    """
    if path == STDIO:
        data = sys.stdin.buffer.read(MAX_INPUT_BYTES + 1)
    else:
        p = Path(path)
        if p.is_dir():
            raise InputError("is a directory, not a file", Span(path, 1, 1))
        try:
            # One byte past the limit is enough to refuse; a device or a pipe that never
            # ends (/dev/zero) is read no further.
            with p.open("rb") as handle:
                data = handle.read(MAX_INPUT_BYTES + 1)
        except FileNotFoundError:
            raise InputError("no such file", Span(path, 1, 1)) from None
        except OSError as error:
            raise InputError(f"cannot read: {error.strerror}", Span(path, 1, 1)) from None
    check_size(len(data), path)
    if b"\x00" in data:
        raise InputError("this is a binary file, not text", Span(path, 1, 1))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data[: error.start].count(b"\n") + 1
        column = error.start - (data.rfind(b"\n", 0, error.start) + 1) + 1
        raise InputError(
            "the file is not valid UTF-8 text", Span(path, line, column),
            hint=f"byte 0x{data[error.start]:02x} cannot be decoded",
        ) from None


def write_atomic(path: str, text: str) -> None:
    """Write `text` to `path` (standard output for `-`) all at once or not at all."""
    if path == STDIO:
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise InputError("the folder for this output does not exist", Span(path, 1, 1))
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
