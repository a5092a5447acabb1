"""Simulated seconds per wall second of the PyBullet Youbot run, and where the time goes.

Runs the default scene (domains/scenes/youbot.toml) headless, with physics on, through
Algorithm 1 with the scene's agents, once per seed, each seed in a fresh process (so
that no seed's timings include another's imports or caches). Reports per seed: ticks,
simulated time, wall time of the run (world loading excluded), sim/wall, the CPU time of the run and sim/CPU (what the run
costs when the machine is shared: wall time then includes waiting for a core), and the
wall time spent stepping the physics, in IK,
in arm planning (collision checks and joint-space OMPL), in base OMPL solves and in
measuring conditions (collision queries for `blocks`, and every fact; OMPL not included).

    python bench/sim.py                 # seeds 0-9
    python bench/sim.py --seeds 0:3
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

ONE_RUN = """
import json, sys, time
from btplan.acting.loop import BlendedLoop
from btplan.lang import load
from btplan.worlds.pybullet import open_world

task = load([sys.argv[1]], None)
world = open_world(task, seed=int(sys.argv[2]))
loop = BlendedLoop(task, world)
agents = world.scene_agents()
began, cpu = time.perf_counter(), time.process_time()
result = loop.run(1500, before_tick=lambda tick: [a.act(world, tick) for a in agents])
wall, cpu = time.perf_counter() - began, time.process_time() - cpu
stats = world.stats()
world.close()
print(json.dumps({"reached": result.reached, "ticks": loop.ticks, "wall": wall, "cpu": cpu,
                  **stats}))
"""

COLUMNS = ("seed", "reached", "ticks", "sim s", "wall s", "sim/wall", "cpu s", "sim/cpu", "physics s",
           "IK s", "arm plan s", "arm OMPL", "base OMPL s", "conditions s", "other s")


def run(seed: int) -> dict[str, float]:
    out = subprocess.run([sys.executable, "-c", ONE_RUN, str(ROOT / "domains" / "youbot.bt"),
                          str(seed)], capture_output=True, text=True, check=True, cwd=ROOT)
    row: dict[str, float] = json.loads(out.stdout.strip().splitlines()[-1])
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", default="0:10", help="A:B, seeds A to B-1")
    args = parser.parse_args()
    first, last = (int(x) for x in args.seeds.split(":"))
    print(f"load average (1, 5, 15 min) at the start: {os.getloadavg()}")
    print("| " + " | ".join(COLUMNS) + " |")
    print("|" + "---|" * len(COLUMNS))
    totals = {"sim": 0.0, "wall": 0.0, "cpu": 0.0, "physics": 0.0, "ik": 0.0, "base": 0.0,
              "conditions": 0.0}
    for seed in range(first, last):
        r = run(seed)
        base = r["ompl_seconds_total"]
        other = r["wall"] - r["physics_seconds"] - r["ik_seconds"] - r["arm_planning_seconds"] \
            - base - r["conditions_seconds"]
        cells = [seed, r["reached"], r["ticks"], f"{r['sim_seconds']:.1f}", f"{r['wall']:.1f}",
                 f"{r['sim_seconds'] / r['wall']:.1f}x", f"{r['cpu']:.1f}",
                 f"{r['sim_seconds'] / r['cpu']:.1f}x", f"{r['physics_seconds']:.1f}",
                 f"{r['ik_seconds']:.2f}", f"{r['arm_planning_seconds']:.2f}",
                 f"{r['arm_ompl_solves']:.0f}", f"{base:.2f}", f"{r['conditions_seconds']:.1f}", f"{other:.1f}"]
        print("| " + " | ".join(str(c) for c in cells) + " |", flush=True)
        totals["sim"] += r["sim_seconds"]
        totals["wall"] += r["wall"]
        totals["cpu"] += r["cpu"]
        totals["physics"] += r["physics_seconds"]
        totals["ik"] += r["ik_seconds"]
        totals["base"] += base
        totals["conditions"] += r["conditions_seconds"]
    print(f"\nload average (1, 5, 15 min) at the end: {os.getloadavg()}")
    print(f"all seeds: {totals['sim']:.1f} s simulated in {totals['wall']:.1f} s wall = "
          f"{totals['sim'] / totals['wall']:.1f}x real time ({totals['cpu']:.1f} s of CPU: "
          f"{totals['sim'] / totals['cpu']:.1f}x); physics alone "
          f"{totals['sim'] / max(totals['physics'], 1e-9):.1f}x real time")
    print(f"wall time in physics {totals['physics']:.1f} s, IK {totals['ik']:.1f} s, base OMPL "
          f"{totals['base']:.1f} s, conditions {totals['conditions']:.1f} s")


if __name__ == "__main__":
    main()
