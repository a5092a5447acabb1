"""Blended acting against replanning and plan repair, over thousands of seeded runs.

The paper's claim (Problem 1) is that a backchained BT copes with external agents more
cheaply than re-planning. This script runs `btplan sweep` on three scenarios (the rows
land in bench/results/), then writes docs/reactivity.md's tables and
docs/reactivity.png from those rows: medians with 95% intervals, the targets met or
missed per rate, and an explanation of every failed run of btplan (does replanning
without a per-tick limit fail on the same seed too?).

Run:  python bench/reactivity.py --sweep [--seeds 1000] [--jobs 2]   (hours on 2 cores)
      python bench/reactivity.py                                    (report from the rows)
The report reads every .parquet and .csv file of bench/results/, so extra seeds can be
swept into files of their own (`--seeds 1000:2000 -o bench/results/obstacle_2.parquet`).
"""

from __future__ import annotations

import argparse
import shlex
import subprocess
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from btplan.sweep import Job, pool
from btplan.sweep.output import markdown_table, plot, read_rows, write_rows
from btplan.sweep.runs import Row
from btplan.sweep.stats import Point, summarize

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"
RATES = "0,0.05,0.1,0.2,0.3"
METHODS = "btplan,replan,repair"
BASELINES = ("replan", "repair")


@dataclass(frozen=True)
class Case:
    scenario: str
    files: tuple[str, ...]


CASES = (
    Case("obstacle", ("domains/pick_place_obstacle.bt",)),
    Case("towers", ("bench/problems/blocksworld_6.bt",)),
    Case("packages", ("bench/problems/logistics_1.bt",)),
)


def command(case: Case, seeds: int, jobs: int) -> list[str]:
    return ["btplan", "sweep", *case.files, "--scenario", case.scenario,
            "--seeds", f"0:{seeds}", "--rates", RATES, "--method", METHODS,
            "-j", str(jobs), "-o", f"bench/results/{case.scenario}.parquet"]


def sweep(seeds: int, jobs: int) -> None:
    RESULTS.mkdir(exist_ok=True)
    for case in CASES:
        args = command(case, seeds, jobs)
        print("$", shlex.join(args), file=sys.stderr)
        subprocess.run(args, cwd=ROOT, check=False)


# --- the report --------------------------------------------------------------------------


def verdicts(points: Sequence[Point]) -> list[tuple[str, ...]]:
    """Per scenario and rate: btplan's planning time against the best baseline's, and more.

    Targets: planning CPU time at most the best baseline's at every rate and 5x lower
    from 0.1; success at least equal; ticks to goal at most 10% above.
    """
    out = []
    keyed = {(p.scenario, p.method, p.rate): p for p in points}
    for p in points:
        if p.method != "btplan":
            continue
        base = [keyed[(p.scenario, m, p.rate)] for m in BASELINES if (p.scenario, m, p.rate) in keyed]
        if not base:
            continue
        best_time = min(b.planning_ms.value for b in base)
        best_success = max(b.success.value for b in base)
        best_ticks = min(b.ticks.value for b in base)
        ratio = best_time / p.planning_ms.value if p.planning_ms.value else float("inf")
        need = 5.0 if p.rate >= 0.1 else 1.0
        out.append((
            p.scenario, f"{p.rate:g}", f"{p.planning_ms.value:.2f}", f"{best_time:.2f}",
            f"{ratio:.2f}x lower " + ("met" if ratio >= need
                                      else f"**missed** (target {need:g}x)"),
            f"{p.success.value:.1%} vs {best_success:.1%} "
            + ("met" if p.success.value >= best_success else "**missed**"),
            f"{p.ticks.value:.0f} vs {best_ticks:.0f} "
            + ("met" if p.ticks.value <= 1.1 * best_ticks else "**missed**"),
        ))
    return out


def explain_failures(rows: Sequence[Row], jobs: int = 1,
                     cache: Path | None = None) -> list[tuple[str, ...]]:
    """For every failed run: does replanning with no per-tick limit fail on that seed too?

    When it does, the disturbed world had no solution within the tick budget for a
    reactive executor either; when it does not, the failure is the method's own. The
    reruns are kept in `cache` (rows of the method replan-unlimited) for the next report.
    """
    known = read_rows(str(cache)) if cache is not None and cache.exists() else []
    failed: dict[tuple[str, float, str], list[int]] = {}
    for r in rows:
        if not r["success"] and not r["error"]:
            key = (r["scenario"], float(r["rate"]), r["method"])
            failed.setdefault(key, []).append(int(r["seed"]))
    verdict = {(r["scenario"], float(r["rate"]), int(r["seed"])): bool(r["success"])
               for r in known}
    for case in CASES:
        needed = sorted({(rate, seed) for (scenario, rate, _), seeds in failed.items()
                         if scenario == case.scenario for seed in seeds
                         if (scenario, rate, seed) not in verdict})
        if not needed:
            continue
        job = Job(tuple(str(ROOT / f) for f in case.files), case.scenario)
        runs = [("replan-unlimited", rate, seed) for rate, seed in needed]
        found: list[Row] = []
        if jobs > 1:
            pool.run_local(job, runs, found.append, jobs)
        else:
            pool.run_serial(job, runs, found.append)
        for row in found:
            verdict[(case.scenario, float(row["rate"]), int(row["seed"]))] = bool(row["success"])
        known += found
    if cache is not None and known:
        write_rows(str(cache), known)
    out = []
    for (scenario, rate, method), seeds in sorted(failed.items()):
        also = sum(1 for s in seeds if not verdict[(scenario, rate, s)])
        out.append((scenario, f"{rate:g}", method, str(len(seeds)), str(also),
                    str(len(seeds) - also)))
    return out


START, END = "<!-- results: bench/reactivity.py -->", "<!-- end of results -->"


def _table(header: Sequence[str], cells: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(c) + " |" for c in cells]
    return "\n".join(lines) + "\n"


def report(rows: Sequence[Row], jobs: int = 1, cache: Path | None = None) -> str:
    points = summarize(rows)
    runs = {(r["scenario"]) for r in rows}
    seeds = {s: len({r["seed"] for r in rows if r["scenario"] == s}) for s in sorted(runs)}
    text = ["Seeds per point: " + ", ".join(f"{s} {n}" for s, n in seeds.items())
            + f"; rates {RATES}; medians [95% interval]; planning time is CPU (process) time;"
            " ticks to goal over the runs that reached it.\n",
            markdown_table(points),
            "\n### Targets (btplan against the best baseline at each point)\n\n",
            _table(("scenario", "rate", "btplan ms", "best baseline ms", "planning time",
                    "success", "ticks to goal"), verdicts(points)),
            "\n### Failed runs\n\n"]
    failures = explain_failures(rows, jobs, cache)
    if failures:
        text.append(_table(("scenario", "rate", "method", "failed runs",
                            "replan-unlimited fails too", "its own failures"), failures))
    else:
        text.append("None.\n")
    return "".join(text)


def fill(page: Path, block: str) -> None:
    old = page.read_text(encoding="utf-8")
    if START not in old or END not in old:
        old += f"\n{START}\n{END}\n"
    before, rest = old.split(START, 1)
    page.write_text(before + START + "\n" + block + END + rest.split(END, 1)[1], encoding="utf-8")


def load_rows(folder: Path) -> list[Row]:
    """Every row of the .parquet and .csv files in `folder`, one per run (later files win)."""
    found: dict[tuple[str, str, float, int], Row] = {}
    for path in sorted([*folder.glob("*.parquet"), *folder.glob("*.csv")]):  # not unlimited/
        for row in read_rows(str(path)):
            found[(row["scenario"], row["method"], float(row["rate"]), int(row["seed"]))] = row
    return list(found.values())


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--sweep", action="store_true", help="run the sweeps first")
    parser.add_argument("--seeds", type=int, default=1000)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    if args.sweep:
        sweep(args.seeds, args.jobs)
    rows = load_rows(RESULTS)
    if not rows:
        print("no rows in bench/results/: run with --sweep first", file=sys.stderr)
        return 1
    block = report(rows, args.jobs, RESULTS / "unlimited" / "reruns.parquet")
    sys.stdout.write(block)
    fill(ROOT / "docs" / "reactivity.md", block)
    plot(summarize(rows), str(ROOT / "docs" / "reactivity.png"))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
