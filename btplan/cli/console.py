"""The consoles of the commands: rich on a terminal, plain text otherwise, rich imported late.

Importing rich's console costs about as much as a small planning run, and most runs
write to a pipe or a file (scripts, benchmarks), where rich prints the text without
its markup anyway. So a command writes through `LazyConsole`: to a stream that is no
terminal it strips the markup itself; on a terminal, or for a rich renderable (a
table), it builds the rich Console on first use. `escape` marks text as literal in
the same way as `rich.markup.escape`, so either path reads it the same.
"""

from __future__ import annotations

import os
import re
import sys

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, TextIO

    from rich.console import Console

_TAG = re.compile(r"(\\*)(\[[a-z#/@][^[]*?])")
"""A markup tag, with the backslashes before it (rich's own pattern of a tag)."""


def escape(text: str) -> str:
    """Make `text` print literally under rich markup: a backslash before every
    tag-like `[...]` (doubling backslashes already there), and none left at the end."""

    def protect(match: re.Match[str]) -> str:
        backslashes, tag = match.groups()
        return f"{backslashes}{backslashes}\\{tag}"

    text = _TAG.sub(protect, text)
    if text.endswith("\\") and not text.endswith("\\\\"):
        return text + "\\"
    return text


def plain(markup: str) -> str:
    """The text of rich markup without its styles: tags dropped, escaped brackets kept."""

    def unmark(match: re.Match[str]) -> str:
        backslashes, tag = match.groups()
        if len(backslashes) % 2:  # an escaped bracket: literal text
            return backslashes[: len(backslashes) // 2] + tag
        return backslashes[: len(backslashes) // 2]

    return _TAG.sub(unmark, markup) if "[" in markup else markup


def _styled() -> bool:
    """Whether rich would style a stream that is no terminal (it does when forced to)."""
    return bool(os.environ.get("FORCE_COLOR") or os.environ.get("TTY_COMPATIBLE") == "1")


class LazyConsole:
    """Standard output or error, printing rich markup; see the module docstring."""

    def __init__(self, stderr: bool = False, rich: Console | None = None) -> None:
        """`rich`: a ready console that then takes every print (a test's terminal)."""
        self.stderr = stderr
        self._rich = rich
        self._given = rich is not None

    @property
    def file(self) -> TextIO:
        """The stream now (test runners swap sys.stdout and sys.stderr)."""
        return sys.stderr if self.stderr else sys.stdout

    @property
    def is_terminal(self) -> bool:
        """Whether the stream is a terminal (a given rich console answers for itself); a closed
        stream counts as none, so output to it stays plain."""
        if self._rich is not None and self._given:
            return self._rich.is_terminal
        try:
            return self.file.isatty()
        except ValueError:  # a closed stream
            return False

    @property
    def rich(self) -> Console:
        """The rich Console for live displays and tables; imported on first use."""
        if self._rich is None:
            from rich.console import Console

            self._rich = Console(stderr=self.stderr, highlight=False, soft_wrap=True)
        return self._rich

    def print(self, text: Any = "", end: str = "\n", markup: bool = True) -> None:
        """Print `text` and `end`; a string bound for no terminal (and no forced colour) is
        written with its markup stripped and without importing rich, anything else goes
        through rich. `markup=False` takes the text as it is."""
        if isinstance(text, str) and not self._given and not self.is_terminal \
                and not _styled():
            self.file.write((plain(text) if markup else text) + end)
            self.file.flush()
            return
        self.rich.print(text, end=end, markup=markup)
