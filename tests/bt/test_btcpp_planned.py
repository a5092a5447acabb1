"""Trees the planner builds for the example domains, exported and run inside BT.CPP.

Each tree is planned, exported to XML, loaded into BehaviorTree.CPP and ticked against
one symbolic world while btplan ticks the same tree against another; both must give the
same status on every tick and execute the same actions to the goal.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.acting.offline import load, plan
from btplan.bt import RUNNING, SUCCESS
from btplan.bt.formats.btcpp import dump_xml, load_xml
from btplan.worlds.symbolic import SymbolicWorld

pytest.importorskip("behaviortreepy")
from btcpp_oracle import BtcppRun

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


@pytest.mark.parametrize("name", ["pick_place", "pick_place_obstacle", "gripper",
                                  "run_alternatives"])
def test_planned_tree_runs_the_same_in_btcpp(name: str) -> None:
    task = load(str(DOMAINS / f"{name}.bt"))
    tree = plan(task).tree
    xml = dump_xml(tree)
    assert dump_xml(load_xml(xml)) == xml
    ours, theirs = SymbolicWorld(task), SymbolicWorld(task)
    run = BtcppRun(xml, theirs)
    for tick in range(1, 500):
        status = tree.tick(ours)
        assert (tick, run.tick()) == (tick, status)
        if status is not RUNNING:
            break
    assert status is SUCCESS
    assert theirs.executed == ours.executed and ours.executed
