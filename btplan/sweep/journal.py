"""The rows of a sweep on disk as they come, so that nothing finished is lost.

A sweep runs for hours and writes its output once, at the end. Every finished row is
also appended, one JSON line in one write, to a side file next to the output
(`rows.csv` → `rows.csv.rows.jsonl`): a full disk at the end, `kill -9` or the OOM
killer leave every finished row there, and `--resume` goes on from them. The side file
is removed once the output is written.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

from btplan.io import write_all
from btplan.sweep.runs import Row

SUFFIX = ".rows.jsonl"


def journal_path(output: str) -> str:
    """The side file of an output."""
    return output + SUFFIX


class RowJournal:
    """Appends rows to the side file of `output`; reads back what an earlier sweep left."""

    def __init__(self, output: str) -> None:
        self.path = journal_path(output)
        self._fd: int | None = None

    def exists(self) -> bool:
        """Whether an earlier sweep left its rows: `--resume` goes on from them, and a sweep
        without it refuses to overwrite them."""
        return Path(self.path).exists()

    def read(self) -> list[Row]:
        """The rows of the side file; a last line cut short by a kill is left out."""
        rows: list[Row] = []
        with open(self.path, encoding="utf-8") as handle:
            for line in handle:
                if not line.endswith("\n"):
                    break
                try:
                    rows.append(json.loads(line))
                except json.JSONDecodeError:
                    break
        return rows

    def open(self, keep: bool) -> None:
        """Start writing: after the rows already there (`keep`), or afresh."""
        flags = os.O_WRONLY | os.O_CREAT | (os.O_APPEND if keep else os.O_TRUNC)
        self._fd = os.open(self.path, flags, 0o666)
        if keep:  # cut a torn last line, so the next row starts on a line of its own
            os.ftruncate(self._fd, Path(self.path).read_bytes().rfind(b"\n") + 1)

    def add(self, row: Row) -> None:
        """Append `row` as one compact JSON line, with no buffer in between: a kill leaves at
        most a torn last line, which `read` drops and `open(keep=True)` cuts. Only once open."""
        assert self._fd is not None
        write_all(self._fd, (json.dumps(row, separators=(",", ":")) + "\n").encode("utf-8"))

    def close(self) -> None:
        """Stop writing; the rows stay on disk for `--resume` until `remove`. Safe to call twice."""
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None

    def remove(self) -> None:
        """Close and delete the side file, once the output holds every row; no error if it is
        gone already."""
        self.close()
        Path(self.path).unlink(missing_ok=True)
