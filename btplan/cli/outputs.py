"""Every file a command writes: checked before the work starts, then written whole.

Users run btplan in scripts and on robots. A bad output path found only after minutes
of planning wastes the work, and a first output written before a second one fails
leaves a mix of old and new files; so each command lists its outputs up front and
`check_outputs` refuses the lot (exit 2, one line naming the flag and the path) before
anything is read or written. Files are then written the way `btplan.io.write_atomic`
does it: a temporary file renamed over the target, with a normal file's mode.

The files that record a run in progress (`--trace`, `--plan-out` of `run`) are the
exception: they are written as the run goes, so that an interrupted or killed run
keeps what it did. `LineStream` writes each line whole, in one system call.
"""

from __future__ import annotations

import errno
import os
import re
import stat
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from types import TracebackType

from btplan.errors import InputError, Interrupted
from btplan.io import STDIO, stream_of, write_all, write_atomic, write_stream
from btplan.records import record

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Self

__all__ = ["STDIO", "LineStream", "Output", "check_outputs", "write_atomic"]


@record(frozen=True, slots=True)
class Output:
    """One output of a command: the flag that names it, the path given (None: not asked for)."""

    flag: str
    path: str | None
    folder: bool = False


def check_outputs(*outputs: Output, inputs: Sequence[str] = ()) -> None:
    """Refuse, before any work, outputs that cannot be written as given.

    At most one output may take standard output (two would interleave; /dev/stdout and
    its aliases count as `-`), no output may be the same file as an input (it would
    destroy it: compared by device and inode, through links) or as another output, and
    each path must be writable: not a folder (or, for a folder output, not a file), in a
    folder that exists, with permission to write there.
    """
    given = [o for o in outputs if o.path is not None]
    on_stdout = [o.flag for o in given if o.path is not None and stream_of(o.path) == 1]
    if len(on_stdout) > 1:
        raise InputError(f"{on_stdout[0]} and {on_stdout[1]} both write to standard output "
                         "('-' or /dev/stdout); send one of them to a file")
    read = {identity(path): path for path in inputs if path != STDIO and os.path.exists(path)}
    seen: dict[object, str] = {}
    for output in given:
        assert output.path is not None
        if stream_of(output.path) is not None:
            if output.folder:
                raise InputError(f"{output.flag} needs a folder, not '{output.path}'")
            continue
        problem = link_problem(output.path) or (
            folder_problem(output.path) if output.folder else file_problem(output.path))
        if problem is not None:
            raise InputError(f"{output.flag} {output.path}: {problem}")
        key = identity(output.path)
        if key in read:
            same = "" if read[key] == output.path else f" {read[key]}"
            raise InputError(f"{output.flag} {output.path} is the input file{same}: writing "
                             "it would destroy the input", hint="write the output elsewhere")
        if key in seen:
            raise InputError(f"{seen[key]} and {output.flag} both write to {output.path}")
        seen[key] = output.flag
    for output in given:
        if output.folder and output.path is not None:
            _check_folder_files(output, [*inputs, *(o.path for o in given
                                                     if o is not output and o.path)])


FOLDER_FILE = re.compile(r"expansion_\d{3,}\.(dot|json)")
"""The files a folder output holds (`--trace-expansions`: one pair per expansion)."""


def _check_folder_files(output: Output, others: Sequence[str]) -> None:
    """Refuse an input or another output that the folder's files would overwrite."""
    assert output.path is not None
    folder = Path(output.path).resolve()
    for other in others:
        if other == STDIO or stream_of(other) is not None:
            continue
        target = Path(other).resolve()
        if target.parent == folder and FOLDER_FILE.fullmatch(target.name):
            raise InputError(f"{output.flag} {output.path} would overwrite {other}",
                             hint="give the expansions a folder of their own")


def identity(path: str) -> object:
    """What makes two paths the same file: device and inode when it exists (links and
    other names of it included), its resolved path when it does not yet."""
    try:
        info = os.stat(path)
    except OSError:
        return Path(path).resolve()
    return (info.st_dev, info.st_ino)


def link_problem(path: str) -> str | None:
    """Why a symbolic link at `path` cannot be written through: a loop of links."""
    try:
        os.stat(path)
    except OSError as error:
        if error.errno == errno.ELOOP:
            return "is a loop of symbolic links"
    return None


def file_problem(path: str) -> str | None:
    """Why a file cannot be written at `path`, or None if it can.

    A device or a pipe (/dev/null) is written in place, so only its own permission
    counts; a link is judged by the file it points to.
    """
    if path.endswith(os.sep):
        return "names a folder, not a file"
    target = Path(os.path.realpath(path))
    if target.is_dir():
        return "is a folder, not a file"
    if target.exists() and not target.is_file():
        return None if os.access(target, os.W_OK) else "no permission to write here"
    folder = target.parent
    if not folder.exists():
        return f"the folder {folder} does not exist"
    if not folder.is_dir():
        return f"{folder} is not a folder"
    if not os.access(folder, os.W_OK | os.X_OK):
        return f"no permission to write in the folder {folder}"
    if target.exists() and not os.access(target, os.W_OK):
        return "no permission to write this file"
    return None


def folder_problem(path: str) -> str | None:
    """Why a folder of outputs cannot be made or written at `path`, or None if it can."""
    target = Path(path)
    if target.is_symlink() and not target.exists():
        return "is a link to a folder that does not exist"
    if target.exists() and not target.is_dir():
        return "is a file, not a folder"
    existing = target
    while not existing.exists():
        existing = existing.parent
    if not existing.is_dir():
        return f"{existing} is not a folder"
    if not os.access(existing, os.W_OK | os.X_OK):
        return f"no permission to write in the folder {existing}"
    return None


PIPE_POLL = 0.05
"""Seconds between two looks for a named pipe's reader."""


def _is_pipe(path: str) -> bool:
    try:
        return stat.S_ISFIFO(os.stat(path).st_mode)
    except OSError:
        return False


class LineStream:
    """A file written line by line while a run goes on; `-` is standard output.

    Each line goes to the file in one `write` call with no buffer in between, so a
    run that is interrupted, or killed outright, leaves every line it finished and
    never half of one. The file is created like any file (0666 less the umask), and
    an existing file keeps its mode.
    """

    def __init__(self, path: str, stop: Callable[[], bool] | None = None) -> None:
        self.path = path
        self.stop = stop
        """Asked while waiting for a named pipe's reader: a signal must not wait for one."""
        self._fd: int | None = None
        self._stream = stream_of(path)
        """A stream of this process (`-`, /dev/stdout, /dev/fd/N): written in place."""

    def __enter__(self) -> Self:
        if self._stream is None:
            self._fd = self._open_pipe() if _is_pipe(self.path) else os.open(
                self.path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666)
        return self

    def _open_pipe(self) -> int:
        """Open a named pipe once it has a reader, without blocking a stop request: a
        plain open() would wait for the reader through every signal."""
        while True:
            try:
                fd = os.open(self.path, os.O_WRONLY | os.O_NONBLOCK)
            except OSError as error:
                if error.errno != errno.ENXIO:  # ENXIO: no reader yet
                    raise
            else:
                os.set_blocking(fd, True)
                return fd
            if self.stop is not None and self.stop():
                raise Interrupted(f"waiting for a reader of {self.path}")
            time.sleep(PIPE_POLL)

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def write_line(self, line: str) -> None:
        """Write `line`, a newline added if it has none, in one write; if that write fails, a file
        is cut back to where the line began, so it still ends on a whole line, and the error is
        raised again."""
        data = (line if line.endswith("\n") else line + "\n")
        if self._fd is None:
            write_stream(self._stream if self._stream is not None else 1, data)
            return
        try:
            start: int | None = os.lseek(self._fd, 0, os.SEEK_CUR)
        except OSError:  # a pipe: nothing to cut back
            start = None
        try:
            write_all(self._fd, data.encode("utf-8"))
        except OSError:
            if start is not None:  # keep the file at a line boundary: cut the torn line
                try:
                    os.ftruncate(self._fd, start)
                    os.lseek(self._fd, start, os.SEEK_SET)
                except OSError:
                    pass
            raise
