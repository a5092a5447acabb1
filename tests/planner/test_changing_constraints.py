"""A path blocked at any time is cleared with the paper's Pick and Place.

MoveTo needs `not blocks(_, t)`. When the sphere blocks the path before the robot
first needs it, the reachability estimate must still count the path as clearable, or
MoveTo(goal) is pruned as unreachable.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.acting.offline import load
from btplan.acting.online import run

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OBSTACLE = load(str(DOMAINS / "pick_place_obstacle.bt"))
BLOCK = ["set:blocks(sphere, tau_goal)@{t}"]


@pytest.mark.parametrize("tick", [1, 2, 5, 6])  # the undisturbed run takes 7 ticks
def test_a_path_blocked_at_any_time_is_cleared_and_the_goal_reached(tick: int) -> None:
    result = run(OBSTACLE, disturb=[s.format(t=tick) for s in BLOCK], max_ticks=200)
    assert result.reached, result.reason
    names = [str(a) for a in result.executed]
    assert "Pick(sphere)" in names
    assert names.index("Pick(sphere)") < names.index("Place(sphere, aside)")
    assert names.index("Place(sphere, aside)") < names.index("Place(cube, goal)")
    assert names[-1] == "Place(cube, goal)"
