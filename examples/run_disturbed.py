"""Plan and act at once while someone takes the cube out of the robot's hand.

The robot picks it up again; the tree does not grow (the paper's Problem 1, first
property). Run from anywhere: python examples/run_disturbed.py
"""

from pathlib import Path

from btplan.acting.offline import load, run

DOMAINS = Path(__file__).resolve().parents[1] / "domains"

task = load(str(DOMAINS / "pick_place.bt"))
calm = run(task)
disturbed = run(task, disturb=["undo:Pick@5"], seed=0)

for name, result in (("calm", calm), ("disturbed", disturbed)):
    total = result.summary()
    print(f"{name}: reached={result.reached} ticks={result.ticks} "
          f"expansions={len(total.expansions)}")
    print("  executed:", ", ".join(total.finished))
    for d in total.disturbances:
        print(f"  tick {d.tick}: {d.description}")
