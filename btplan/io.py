"""Reading inputs and writing outputs the way every command does it.

Output files are written to a temporary file in the same folder and then renamed over
the target, so a crash or a bad input never leaves half a file behind.
"""

from __future__ import annotations

import os
import stat
import sys
from collections.abc import Iterable
from pathlib import Path

from btplan.errors import InputError, Span
from btplan.limits import MAX_INPUT_BYTES, check_size

STDIO = "-"

NAME_MAX = 255
"""Bytes in one file name on the file systems btplan writes to (ext4, xfs, tmpfs, APFS)."""

_STREAM_PATHS = {"/dev/stdin": 0, "/dev/stdout": 1, "/dev/stderr": 2}


def stream_of(path: str) -> int | None:
    """The file descriptor a path names when it is a stream of this process: `-` (standard
    output), /dev/stdout, /dev/stderr, /dev/fd/N or /proc/self/fd/N; else None.

    Such a path is written in place, never renamed over: /dev/stdout redirected to a
    file is that file, and a rename would put the output where the shell no longer looks.
    """
    if path == STDIO:
        return 1
    if path in _STREAM_PATHS:
        return _STREAM_PATHS[path]
    for prefix in ("/dev/fd/", "/proc/self/fd/", f"/proc/{os.getpid()}/fd/"):
        if path.startswith(prefix) and path[len(prefix):].isdigit():
            return int(path[len(prefix):])
    return None


def write_stream(fd: int, text: str) -> None:
    """Write `text` to the stream `fd` (standard output and error through Python's own)."""
    if fd in (1, 2):
        stream = sys.stdout if fd == 1 else sys.stderr
        stream.write(text)
        stream.flush()
        return
    write_all(fd, text.encode("utf-8"))


def write_all(fd: int, data: bytes) -> None:
    """Every byte of `data` to the file descriptor `fd` (os.write may take fewer)."""
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


FIRST_READ = 1 << 16
"""Bytes read first from an input file (less than MAX_INPUT_BYTES): most inputs whole."""


def read_text(path: str) -> str:
    """Read a UTF-8 text file, or standard input for `-`, with errors a user can act on;
    a leading byte order mark is dropped and line ends become LF.

    At most MAX_INPUT_BYTES are read (btplan/limits.py).
    """
    if path == STDIO:
        data = sys.stdin.buffer.read(MAX_INPUT_BYTES + 1)
    else:
        try:
            # One byte past the limit is enough to refuse; a device or a pipe that never
            # ends (/dev/zero) is read no further. A first read of FIRST_READ bytes takes
            # a small file whole: asked for the whole limit at once, Python makes a
            # buffer of that size, which cost a small problem's reading 18 us of 370.
            with open(path, "rb") as handle:
                data = handle.read(FIRST_READ)
                if len(data) == FIRST_READ:
                    data += handle.read(MAX_INPUT_BYTES + 1 - FIRST_READ)
        except FileNotFoundError:
            raise InputError("no such file", Span(path, 1, 1)) from None
        except OSError as error:
            if os.path.isdir(path):  # opening one refuses it, in words that differ by system
                raise InputError("is a directory, not a file", Span(path, 1, 1)) from None
            raise InputError(f"cannot read: {error.strerror}", Span(path, 1, 1)) from None
    check_size(len(data), path)
    if b"\x00" in data:
        raise InputError("this is a binary file, not text", Span(path, 1, 1))
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = data[: error.start].count(b"\n") + 1
        column = error.start - (data.rfind(b"\n", 0, error.start) + 1) + 1
        raise InputError(
            "the file is not valid UTF-8 text", Span(path, line, column),
            hint=f"byte 0x{data[error.start]:02x} cannot be decoded",
        ) from None
    # A byte order mark, as some Windows editors write it, is not part of the text; and
    # a line ends at CR LF or at a lone CR (old Mac files) as at LF, as editors read them.
    if text.startswith("\ufeff"):
        text = text[1:]
    return text.replace("\r\n", "\n").replace("\r", "\n") if "\r" in text else text


def write_atomic(path: str, text: str) -> None:
    """Write `text` to `path` (standard output for `-`) all at once or not at all; a
    stream of this process (/dev/stdout, /dev/fd/N) is written in place (`stream_of`)."""
    fd = stream_of(path)
    if fd is not None:
        write_stream(fd, text)
        return
    write_bytes_atomic(path, text.encode("utf-8"))


def write_pieces_atomic(path: str, pieces: Iterable[str]) -> None:
    """`write_atomic` of the text `pieces` make, each encoded and written as it comes
    (`write_chunks_atomic`), so that a large output is never whole in memory, let alone
    twice (as text and as bytes). A stream of this process gets the text whole: nothing
    of it is written when making a piece fails."""
    fd = stream_of(path)
    if fd is not None:
        write_stream(fd, "".join(pieces))
        return
    write_chunks_atomic(path, (piece.encode("utf-8") for piece in pieces))


def write_bytes_atomic(path: str, data: bytes) -> None:
    """Write `data` to `path` all at once or not at all (`write_chunks_atomic`)."""
    write_chunks_atomic(path, (data,))


def write_chunks_atomic(path: str, chunks: Iterable[bytes]) -> None:
    """Write `chunks` to a temporary file beside `path`, then rename it over `path`.

    The temporary file is private (mkstemp), so it gets the mode a plain `open` would
    have given: the existing file's mode, or 0666 less the user's umask. Otherwise every
    output would be readable by its owner only. A symbolic link is written through (the
    file it points to is replaced, not the link), and a target that is not a regular
    file (/dev/null, a named pipe, a terminal) is written in place: renaming over it
    would replace a device with a file.
    """
    target = Path(os.path.realpath(path))
    try:
        info: os.stat_result | None = target.stat()
    except OSError:
        info = None
    if info is not None and not stat.S_ISREG(info.st_mode):
        with open(target, "wb") as stream:
            for chunk in chunks:
                stream.write(chunk)
        return
    folder = target.parent
    if not folder.is_dir():
        raise InputError("the folder for this output does not exist", Span(path, 1, 1))
    mode = output_mode(info)
    fd, tmp = _temporary(folder, target.name)
    try:
        with os.fdopen(fd, "wb") as handle:
            for chunk in chunks:
                handle.write(chunk)
            os.fchmod(handle.fileno(), mode)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _temporary(folder: Path, name: str) -> tuple[int, str]:
    """A new file of our own beside the target, as `tempfile.mkstemp` makes one (mode 0600,
    never an existing file); written here because importing tempfile costs `btplan plan`
    more start-up time than writing its outputs."""
    # A name may be 255 bytes long; the temporary one must fit too, so a long target's
    # name is cut (at a character boundary) to leave room for the marks around it.
    room = NAME_MAX - len(f"..{os.getpid()}-00000000.tmp")
    short = name.encode("utf-8")[:room].decode("utf-8", "ignore")
    for _ in range(100):
        tmp = str(folder / f".{short}.{os.getpid()}-{os.urandom(4).hex()}.tmp")
        try:
            return os.open(tmp, os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0),
                           0o600), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"no free temporary name beside {name}")


def output_mode(existing: os.stat_result | None) -> int:
    """The mode a plain `open` gives: an existing file's own, else 0666 less the umask.

    Files finished under a private temporary name (mkstemp) take it before the rename.
    """
    return stat.S_IMODE(existing.st_mode) if existing is not None else 0o666 & ~current_umask()


def current_umask() -> int:
    """The process umask; reading it means setting it, so it is put back at once."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask
