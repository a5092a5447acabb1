"""Why the loop stopped planning, in words: the messages of its planning errors.

They name what the search did (how many expansions, which conditions most often, the
last actions) so that a user can tell a domain without a way from a search gone round.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Collection, Sequence

from btplan.bt import FAILURE, Action, Node
from btplan.model import GroundLiteral
from btplan.planner import AchieverIndex

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol

    from btplan.acting.skills import Skills
else:
    Protocol = object  # a protocol only types: a plain base at run time


class _Named(Protocol):
    """Anything with a `condition`: an Expansion of the loop."""

    condition: str


def most_expanded(expansions: Sequence[_Named], count: int = 3) -> str:
    """The conditions expanded most often, `on(a, b) (7)`: where the search went round."""
    tally = Counter(e.condition for e in expansions)
    return ", ".join(f"{c} ({n})" for c, n in tally.most_common(count))


def no_achiever_reason(missing: Sequence[GroundLiteral], index: AchieverIndex,
                       circular: Collection[GroundLiteral], expansions: int,
                       skills: Skills) -> str:
    """Say which kind of dead end it is: no achiever at all, or none from here."""
    never = sorted({str(c) for c in missing if not index.has_effect(c)})
    cycled = sorted({str(c) for c in missing if c in circular})
    lost = sorted({str(c) for c in missing if index.has_effect(c) and c not in circular})
    parts = []
    if cycled:
        parts.append(
            f"stuck after {expansions} expansions: every achiever of "
            + " or ".join(cycled) + " needs a condition that an enclosing fallback is"
            " already trying to achieve (the tree chose an order it cannot complete;"
            " the search, not the domain, is at fault)")
    if never:
        parts.append("no action of the domain can make " + " or ".join(never) + " hold")
    if lost:
        recent = [str(a) for a in skills.executed[-4:]]
        parts.append(
            f"stuck after {expansions} expansions: no action can make "
            + " or ".join(lost) + " hold from the state the tree led to (every achiever"
            " needs something that can no longer be brought about, even ignoring deletes)"
            + (f"; last actions: {', '.join(recent)}" if recent else "")
        )
    return "; ".join(parts)


def failing_actions(root: Node) -> list[str]:
    """The actions that failed on the last tick, by name."""
    return sorted({n.name for n in root.walk() if isinstance(n, Action) and n.status is FAILURE})


def world_says(skills: Skills) -> str:
    """What the world knows of why it may be stuck (`dead_ends`: a stale sensor, a grasp
    that cannot work), as "; ..." to add to a reason, or ""."""
    world = skills.world
    found = world.dead_ends() if skills.capabilities.dead_ends else []  # type: ignore[attr-defined]
    return f"; {'; '.join(found)}" if found else ""


def loop_reason(expansions: int, skills: Skills) -> str:
    """The world came back to a state it was in, under the same tree."""
    recent = [str(a) for a in skills.executed[-6:]]
    tail = f"; last actions: {', '.join(recent)}" if recent else ""
    known = world_says(skills)
    return (
        "the world came back to an earlier state with no new expansion "
        f"(after {expansions} expansions){known}{tail}"
    )
