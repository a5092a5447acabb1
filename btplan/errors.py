"""The exceptions btplan raises on purpose; one root so callers catch one family.

This module imports nothing else from btplan, so every layer may use it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
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


class MissingExtraError(BtplanError):
    """An optional dependency a feature needs is not installed; the message names the extra."""
