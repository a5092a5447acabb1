"""Save a tree as BehaviorTree.CPP v4 XML, loadable by BT.CPP and Groot2.

The tree is the one grown while acting in the paper's Example 2: the path to the goal
is blocked at tick 5, while the robot carries the cube, so it holds the subtree that picks the sphere and places it aside,
which no offline plan needs.
Run from anywhere: python examples/export_xml.py [OUT.xml]   (default: standard output)
"""

import sys
from pathlib import Path

from btplan.acting.offline import load, run
from btplan.bt.formats import dump
from btplan.io import write_atomic

DOMAINS = Path(__file__).resolve().parents[1] / "domains"

task = load(str(DOMAINS / "pick_place_obstacle.bt"))
result = run(task, disturb=["set:blocks(sphere, tau_goal)@5"])
write_atomic(sys.argv[1] if len(sys.argv) > 1 else "-", dump(result.tree, "xml"))
