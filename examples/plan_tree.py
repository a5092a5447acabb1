"""Load the paper's Example 1 and plan a Behavior Tree for it, offline.

Run from anywhere: python examples/plan_tree.py
"""

from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.bt.formats import dump

DOMAINS = Path(__file__).resolve().parents[1] / "domains"

task = load(str(DOMAINS / "pick_place.bt"))
result = plan(task)

print(dump(result.tree, "ascii"))
print(f"{result.stats.expansions} expansions, {result.stats.tree_size} nodes")
print("the robot would do:", ", ".join(str(a) for a in result.executed))
