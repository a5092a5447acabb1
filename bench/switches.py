"""One switch of the acting loop on and off, on the reactivity sweep's scenarios.

The design records of the acting loop (docs/design/acting-*.md) say what each switch of
`ActingConfig` buys; this script measures it on the same seeded disturbances the
reactivity sweep uses (bench/reactivity.py), the default preset with the switch on and
with it off, side by side in one process: success, median ticks to the goal, median
planner calls and median planning CPU per run.

    python bench/switches.py leave_plan_once_departed
    python bench/switches.py plan_before_acting --scenarios towers --rates 0.1,0.3 --seeds 100
"""

from __future__ import annotations

import argparse
import time
from dataclasses import fields
from pathlib import Path
from statistics import median

import btplan
from btplan.acting.config import ActingConfig
from btplan.model import Task
from btplan.sweep.scenarios import resolve
from btplan.worlds.symbolic import SymbolicWorld

from reactivity import CASES  # the scenarios the sweep runs, and their problems

ROOT = Path(__file__).resolve().parents[1]
FILES = {case.scenario: case.files for case in CASES}


def runs(scenario: str, rate: float, seeds: int, config: ActingConfig
         ) -> list[tuple[bool, int, int, float]]:
    """(reached, ticks, planner calls, planning CPU seconds) of each seed's run."""
    chosen = resolve(scenario)
    task: Task = chosen.prepare(btplan.load(*(str(ROOT / f) for f in FILES[scenario])))
    out = []
    for seed in range(seeds):
        outcome = btplan.run(task, world=SymbolicWorld(task, seed=seed),
                             agents=chosen.agents(task, rate, seed), seed=seed,
                             max_ticks=chosen.max_ticks, config=config)
        totals = outcome.summary()
        out.append((outcome.reached, outcome.ticks, totals.count("expansions"),
                    totals.planning_seconds))
    return out


def row(label: str, measured: list[tuple[bool, int, int, float]]) -> str:
    reached = [m for m in measured if m[0]]
    ticks = median(m[1] for m in reached) if reached else float("nan")
    return (f"{label:<4} {len(reached):>4}/{len(measured):<4} {ticks:>8.1f} "
            f"{median(m[2] for m in measured):>7.1f} "
            f"{median(m[3] for m in measured) * 1000:>9.2f}")


def main() -> None:
    switches = sorted(f.name for f in fields(ActingConfig)
                      if isinstance(getattr(ActingConfig(), f.name), bool))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("switch", choices=switches, help="the ActingConfig switch to compare")
    parser.add_argument("--scenarios", default="obstacle,towers,packages")
    parser.add_argument("--rates", default="0,0.1,0.2,0.3")
    parser.add_argument("--seeds", type=int, default=30, help="seeds 0..N-1 at each rate")
    args = parser.parse_args()
    started = time.strftime("%Y-%m-%d")
    print(f"$ python bench/switches.py {args.switch} --scenarios {args.scenarios} "
          f"--rates {args.rates} --seeds {args.seeds}   ({started})")
    print("default preset with the switch on and off; medians over the seeds (ticks: of "
          "the runs that reached the goal)")
    print(f"{'scenario':<9} {'rate':>5} {'':<4} {'reached':>9} {'ticks':>8} {'calls':>7} "
          f"{'plan ms':>9}")
    for scenario in args.scenarios.split(","):
        for rate in (float(r) for r in args.rates.split(",")):
            for label, on in (("on", True), ("off", False)):
                config = ActingConfig.default(**{args.switch: on})
                print(f"{scenario:<9} {rate:>5g} "
                      + row(label, runs(scenario, rate, args.seeds, config)), flush=True)


if __name__ == "__main__":
    main()
