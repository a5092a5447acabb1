"""Runs of the `shove` sweep that went round before, reaching the goal now.

Seed 4 at p = 0.01: green, once on the path ahead, is picked up to be carried to the
goal; as the fingers close, the check of that path counts the cube in hand as not yet
put aside, and the branch that puts it aside starts the same Pick again. The pick
restarted every time, and the world came back to the same state ("the world came back
to an earlier state with no new expansion"). Finishing the halted action first
(btplan.acting.departures.finish; it is the same action) lets the pick lift the cube.
Seed 7 at p = 0: the tree went between two moves as a path was measured blocked, then
free; finishing first takes another course there, which does not meet it. Both went
round without it, with the deeper look the sweep runs the simulator with.
"""

from __future__ import annotations

import pytest
from sim_scenes import YOUBOT

from btplan.sweep import Job
from btplan.sweep.runs import run_one


@pytest.mark.slow
@pytest.mark.parametrize(("rate", "seed"), [(0.0, 7), (0.01, 4)])
def test_a_shove_run_that_went_round_reaches_the_goal(rate: float, seed: int) -> None:
    pytest.importorskip("pybullet")
    row = run_one(Job(files=(str(YOUBOT),), scenario="shove", sim="pybullet"), "btplan",
                  rate, seed)
    assert row["error"] == ""
    assert row["success"], row["reason"]
    assert row["actions"] > 0
