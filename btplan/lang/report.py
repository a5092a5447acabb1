"""Collect several mistakes of one input, so a user can fix them in one pass.

Warnings are collected alongside: legal input that is almost certainly not what was
meant (a goal no action can reach). The library returns them; `btplan check` prints them.

Checks run per declaration, per literal and per fact; a mistake in one does not hide
the others. Callers that show one error see the first (`InputErrors` is an InputError);
`btplan check` shows them all.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from btplan.errors import InputError

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import ParamSpec, TypeVar

    P = ParamSpec("P")
    R = TypeVar("R")

LIMIT = 25
"""After this many mistakes the rest are usually consequences; stop there."""


class InputErrors(InputError):
    """Several located mistakes; message, span and hint are those of the first."""

    def __init__(self, errors: list[InputError]) -> None:
        first = errors[0]
        super().__init__(first.message, first.span, first.hint, first.source_line)
        self.errors = tuple(errors)


class Report:
    """Runs checks, keeps their InputErrors, and raises them together at the end."""

    def __init__(self) -> None:
        self.errors: list[InputError] = []
        self.warnings: list[InputError] = []
        """Located remarks on legal input that is very likely a mistake; never raised."""

    def warn(self, remark: InputError) -> None:
        """Keep a remark on legal input that is likely a mistake: returned, never raised, and not
        counted toward LIMIT."""
        self.warnings.append(remark)

    def add(self, error: InputError) -> None:
        """Keep `error`, or each member of an InputErrors; past LIMIT mistakes raise them all at
        once, since the rest are usually consequences."""
        members = error.errors if isinstance(error, InputErrors) else (error,)
        for member in members:
            if len(self.errors) >= LIMIT:
                raise InputErrors(self.errors)
            self.errors.append(member)

    def attempt(self, check: Callable[P, R], *args: P.args, **kwargs: P.kwargs) -> R | None:
        """The result of `check`, or None after recording its InputError."""
        try:
            return check(*args, **kwargs)
        except InputError as error:
            self.add(error)
            return None

    def raise_errors(self, paths: Sequence[str] = ()) -> None:
        """Raise what was found, in reading order: by input (as in `paths`), line, column."""
        if len(self.errors) == 1:
            raise self.errors[0]
        if self.errors:
            order = {path: index for index, path in enumerate(paths)}

            def place(error: InputError) -> tuple[int, int, int]:
                if error.span is None:
                    return (-1, 0, 0)
                return (order.get(error.span.path, len(order)), error.span.line, error.span.column)

            raise InputErrors(sorted(self.errors, key=place))
