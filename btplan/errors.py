"""The exceptions btplan raises on purpose; one root so callers catch one family.

This module imports nothing else from btplan, so every layer may use it.
"""

from __future__ import annotations

from btplan.records import record

EXCERPT_WIDTH = 100
"""Characters of the offending line shown around the caret; a one-line file of 30 KB
would otherwise be echoed whole into the terminal."""


def excerpt(line: str, column: int, width: int = EXCERPT_WIDTH) -> tuple[str, int]:
    """At most about `width` characters of `line` around `column`, and the caret's new column.

    A tab is shown as one space and any other character a terminal would act on
    (escapes, carriage returns) as '?', one for one; a cut is marked with '...' at
    either end. So the caret still points at the mistake.
    """
    text = line.rstrip("\r\n").replace("\t", " ")
    column = min(max(column, 1), len(text) + 1)
    start = max(0, min(column - 1 - width // 2, len(text) - width))
    shown = "".join(c if c.isprintable() else "?" for c in text[start:start + width])
    caret = column - start
    if start > 0:
        shown, caret = "..." + shown, caret + 3
    if start + width < len(text):
        shown += "..."
    return shown, caret



@record(frozen=True, slots=True)
class Span:
    """A place in an input: 1-based line and column, as editors count."""

    path: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"


class BtplanError(Exception):
    """Root of every error btplan raises on purpose."""


class InputError(BtplanError):
    """Bad input (a file, a spec, a flag); the CLI prints it with a caret and exits 2.

    `source_line` is the text of the offending line when it is known, so the
    message can be shown with a caret even for input that did not come from a file.
    """

    def __init__(
        self,
        message: str,
        span: Span | None = None,
        hint: str | None = None,
        source_line: str | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.span = span
        self.hint = hint
        self.source_line = source_line

    def __str__(self) -> str:
        where = f"{self.span}: " if self.span else ""
        return f"{where}{self.message}" + (f" ({self.hint})" if self.hint else "")

    def excerpt(self) -> tuple[str, int] | None:
        """The offending line cut around the column, and the caret's 0-based offset in it."""
        if self.source_line is None or self.span is None:
            return None
        shown, column = excerpt(self.source_line, self.span.column)
        return shown, column - 1


class PlanningError(BtplanError):
    """The planner could not produce a tree that reaches the goal; the CLI exits 1."""

    def __init__(self, reason: str) -> None:
        super().__init__(reason)
        self.reason = reason


class NoAchieverError(PlanningError):
    """A failed condition has no action that can make it true."""


class UnresolvableConflictError(PlanningError):
    """No position of a new subtree is free of conflicts."""


class NoProgressError(PlanningError):
    """The acting loop revisits a world state without expanding the tree."""


class BudgetExceededError(PlanningError):
    """A bound given by the user (expansions, ticks, time) ran out first."""


class WorldError(BtplanError):
    """A world backend cannot do what it was asked (missing extra, bad scene)."""


class Interrupted(BtplanError):
    """The user stopped the work (Ctrl-C, a termination signal) at a tick boundary.

    `progress` says what was done by then, for the summary the CLI prints.
    """

    def __init__(self, progress: str) -> None:
        super().__init__(f"interrupted after {progress}")
        self.progress = progress


class MissingExtraError(BtplanError):
    """An optional dependency a feature needs is not installed; the message names the extra."""


class SkillError(BtplanError):
    """A robot's skill raised, and the run was set to stop on it (`stop_on_skill_error`).

    `action` names the grounded action, `reason` the skill's own message."""

    def __init__(self, action: str, reason: str) -> None:
        super().__init__(f"{action} raised: {reason}")
        self.action, self.reason = action, reason
