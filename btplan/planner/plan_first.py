"""The shape of a tree that runs a plan first, ahead of the backchained tree.

Offline planning puts a shorter plan ahead of the tree backchaining grew
(btplan.acting.offline.improved builds it):

    Retry(Sequence(Fallback(the goals hold, step n, ..., step 1, the backchained tree),
                   all goals hold))

Acting needs to find the backchained part again to leave the plan once the world
departs from it (btplan.acting.departures.leave_plan); the names below tie the two.
"""

from __future__ import annotations

from btplan.bt import Node

__all__ = ["IMPROVED", "UNTIL_DONE", "backchained_part"]

IMPROVED = "shorter plan first"
"""Name of the Fallback that holds the shorter plan's steps ahead of the backchained tree."""

UNTIL_DONE = "step by step until the goals hold"
"""Name of the Retry at the root: a step that finishes within its tick leaves the goals
not yet true, and the final check fails; the Retry answers RUNNING then (BT.CPP 4's
RetryUntilSuccessful tries a child that failed at once again on the next tick), so the
tree reports FAILURE only when it is stuck: after twice as many failed ticks as the
plan has steps."""


def backchained_part(root: Node) -> Node | None:
    """The backchained tree inside a tree that btplan.acting.offline.improved.plan_first
    made, or None for any other tree.

    An acting run leaves the shorter plan once the world departs from it: the plan's
    steps, picked up again wherever one fits, would otherwise take turns with the
    backchained tree that reacts to the departure (btplan.acting.departures.leave_plan)."""
    if root.name != UNTIL_DONE or not root.children:
        return None
    ahead = root.children[0].children[0] if root.children[0].children else None
    if ahead is None or ahead.name != IMPROVED or not ahead.children:
        return None
    return ahead.children[-1]
