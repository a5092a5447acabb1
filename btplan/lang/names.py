"""Name lookups shared by the checks: duplicates and "did you mean" hints."""

from __future__ import annotations

from collections.abc import Iterable

from btplan.lang.report import Report
from btplan.lang.syntax import Name


def suggest(name: str, known: Iterable[str]) -> str | None:
    """A "did you mean" hint from the closest known name; sorted so runs agree."""
    from difflib import get_close_matches  # only a mistake needs it: not imported at start

    near = get_close_matches(name, sorted(known), n=1)
    return f"did you mean '{near[0]}'?" if near else None


def check_unique(names: Iterable[Name], what: str, report: Report | None = None) -> None:
    """Reject every later declaration of a name, pointing at the first."""
    seen: dict[str, Name] = {}
    for name in names:
        if name.text in seen:
            first = seen[name.text].at.span
            error = name.at.error(
                f"{what} '{name.text}' is declared twice", f"first declared at {first}"
            )
            if report is None:
                raise error
            report.add(error)
        else:
            seen[name.text] = name
