"""Telling a loop that goes round in circles from one that makes progress.

When the world comes back to a state it was in, under the same tree (no expansion in
between) and with no outside change, the tree will do what it did from there before:
the loop goes round. An outside change is one seen between two ticks, or one a world
counts in `outside_changes` (agents that act while the robot does, as in the PyBullet
world). In a `continuous` world, where facts change while an action runs (a robot
driving past a cube), states are compared only on ticks where an action ended: passing
by the same place twice within one action is not a loop, and a loop of actions still
repeats its states there. A world that learns from a failed action (the PyBullet arm
remembers the sides of a cube it failed to grasp from, and tries another) counts what it
learned in `lessons`: a state seen before a new lesson is not a loop yet. Each of these
is a capability the world declares (btplan.robot.Capabilities).
"""

from __future__ import annotations

from btplan.model import Atom

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.acting.skills import Skills


class Circles:
    """The states seen since the last outside change, under the tree as it is now.

    A state under a tree that has grown since, or before a new lesson, can never make a
    loop again, so those are forgotten as the tree grows. The others are kept as what
    changed since the first of them (`anchor`): whole states took 28 kB each on
    visit-all, whose grid is in every state, and 13 MB over a 450-step plan.
    """

    def __init__(self) -> None:
        self._seen: set[tuple[frozenset[Atom], frozenset[Atom]]] = set()
        self._anchor: frozenset[Atom] | None = None
        self._under: tuple[int, int] = (-1, -1)
        """The expansions and lessons the states seen were seen under."""
        self._outside = 0
        self._ended = 0

    def forget(self) -> None:
        """A repeated state is no longer a loop (an outside change, another world)."""
        self._seen.clear()
        self._anchor = None

    def repeated(self, skills: Skills, before: frozenset[Atom], after: frozenset[Atom],
                 expansions: int) -> bool:
        """Record the state after a tick; True when the loop was in it before."""
        declared, world = skills.capabilities, skills.world
        outside = (int(world.outside_changes)  # type: ignore[attr-defined]
                   if declared.outside_changes else 0)
        if outside != self._outside:
            # Someone else acted while the tree ticked: a repeated state is no longer a loop.
            self._outside = outside
            self.forget()
        ended = skills.ended
        boundary = ended != self._ended or not declared.continuous
        self._ended = ended
        if after == before or not boundary:
            return False
        lessons = int(world.lessons) if declared.lessons else 0  # type: ignore[attr-defined]
        if (expansions, lessons) != self._under:
            self._under = (expansions, lessons)
            self.forget()  # what was seen under another tree or with less learned
        anchor = self._anchor
        if anchor is None:
            anchor = self._anchor = after
        key = (after - anchor, anchor - after)
        if key in self._seen:
            return True
        self._seen.add(key)
        return False
