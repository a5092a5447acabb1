"""Blended acting against replanning and plan repair, over thousands of seeded runs.

The paper's claim (Problem 1) is that a backchained BT copes with external agents more
cheaply than re-planning. This script runs `btplan sweep` on three scenarios (the rows
land in bench/results/), then writes the tables of docs/results/reactivity.md and
docs/images/results-reactivity.png from those rows: medians with 95% intervals, the
targets met or missed per rate, and an explanation of every failed run of btplan (does
replanning without a per-tick limit fail on the same seed too?). How a sweep works is
in docs/reactivity.md.

Run:  python bench/reactivity.py --sweep [--first 0] [--seeds 1000] [--jobs 2]   (hours)
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

from btplan.sweep import Job, explain, pool
from btplan.sweep.output import markdown_table, plot, read_rows, write_rows
from btplan.sweep.runs import Row
from btplan.sweep.stats import Point, median_interval, summarize

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"
RATES = "0,0.05,0.1,0.2,0.3"
METHODS = "btplan,replan,repair"
BASELINES = ("replan", "repair")
PAGE = ROOT / "docs" / "results" / "reactivity.md"
PLOT = ROOT / "docs" / "images" / "results-reactivity.png"


@dataclass(frozen=True)
class Case:
    scenario: str
    files: tuple[str, ...]


CASES = (
    Case("obstacle", ("domains/pick_place_obstacle.bt",)),
    Case("towers", ("bench/problems/blocksworld_6.bt",)),
    Case("packages", ("bench/problems/logistics_1.bt",)),
)


CHUNK = 100
"""Seeds per sweep command: a sweep cut short still has every rate and method."""


def command(case: Case, seeds: range, jobs: int, out: Path) -> list[str]:
    return ["btplan", "sweep", *case.files, "--scenario", case.scenario,
            "--seeds", f"{seeds.start}:{seeds.stop}", "--rates", RATES, "--method", METHODS,
            "-j", str(jobs), "-q", "-o", str(out)]


def sweep(seeds: int, jobs: int, scenarios: Sequence[str], first: int = 0) -> None:
    """Sweep seeds first..seeds-1 of the chosen scenarios in chunks of CHUNK seeds,
    interleaved, then merge each scenario's chunks into bench/results/SCENARIO.parquet,
    over the rows it held for other seeds (a failed chunk is left out)."""
    cases = [c for c in CASES if c.scenario in scenarios]
    parts = RESULTS / "parts"
    parts.mkdir(parents=True, exist_ok=True)
    for start in range(first, seeds, CHUNK):
        chunk = range(start, min(start + CHUNK, seeds))
        for case in cases:
            out = parts / f"{case.scenario}_{chunk.start}.parquet"
            args = command(case, chunk, jobs, out)
            print("$", shlex.join(args), file=sys.stderr)
            if subprocess.run(args, cwd=ROOT, check=False).returncode != 0:
                out.unlink(missing_ok=True)
    for case in cases:
        merged = RESULTS / f"{case.scenario}.parquet"
        rows = [r for path in sorted(parts.glob(f"{case.scenario}_*.parquet"))
                for r in read_rows(str(path))]
        if not rows:
            continue
        new = {(r["method"], float(r["rate"]), int(r["seed"])) for r in rows}
        kept = [r for r in (read_rows(str(merged)) if merged.exists() else [])
                if (r["method"], float(r["rate"]), int(r["seed"])) not in new]
        write_rows(str(merged), kept + rows)


# --- the report --------------------------------------------------------------------------


def totals(rows: Sequence[Row]) -> dict[tuple[str, str, float], float]:
    """Median CPU ms of planning and set-up together, per point (rows written before
    set-up was timed apart counted it in their planning time)."""
    groups: dict[tuple[str, str, float], list[float]] = {}
    for r in rows:
        if not r["error"]:
            seconds = float(r["planning_seconds"]) + float(r.get("setup_seconds") or 0.0)
            groups.setdefault((r["scenario"], r["method"], float(r["rate"])), []).append(seconds)
    return {key: 1000 * median_interval(values).value for key, values in groups.items()}


def _ratio(mine: float, best: float, need: float) -> str:
    ratio = best / mine if mine else float("inf")
    return f"{ratio:.2f}x " + ("met" if ratio >= need else f"**missed** (target {need:g}x)")


def verdicts(points: Sequence[Point], rows: Sequence[Row]) -> list[tuple[str, ...]]:
    """Per scenario and rate: btplan's planning time against the best baseline's, and more.

    Targets: planning CPU time at most the best baseline's at every rate and 5x lower
    from 0.1; success at least equal; ticks to goal at most 10% above. Planning time
    is judged twice: the expansions or searches alone, and with the task's set-up.
    """
    out: list[tuple[str, ...]] = []
    keyed = {(p.scenario, p.method, p.rate): p for p in points}
    total = totals(rows)
    for p in points:
        if p.method != "btplan":
            continue
        base = [keyed[(p.scenario, m, p.rate)] for m in BASELINES if (p.scenario, m, p.rate) in keyed]
        if not base:
            continue
        best_time = min(b.planning_ms.value for b in base)
        best_total = min(total[(b.scenario, b.method, b.rate)] for b in base)
        best_success = max(b.success.value for b in base)
        best_ticks = min(b.ticks.value for b in base)
        need = 5.0 if p.rate >= 0.1 else 1.0
        mine_total = total[(p.scenario, p.method, p.rate)]
        reacting = _above_undisturbed(p, base, keyed)
        out.append((
            p.scenario, f"{p.rate:g}", f"{p.planning_ms.value:.2f} vs {best_time:.2f}",
            _ratio(p.planning_ms.value, best_time, need),
            f"{mine_total:.2f} vs {best_total:.2f}", _ratio(mine_total, best_total, need),
            f"{p.success.value:.1%} vs {best_success:.1%} "
            + ("met" if p.success.value >= best_success else "**missed**"),
            f"{p.ticks.value:.0f} vs {best_ticks:.0f} "
            + ("met" if p.ticks.value <= 1.1 * best_ticks else "**missed**"),
            reacting,
        ))
    return out


def _above_undisturbed(p: Point, base: Sequence[Point], keyed: dict[tuple[str, str, float], Point]
                       ) -> str:
    """Planning CPU spent on reacting: each method's median at this rate less its median
    with no disturbance (which both pay before the first action), btplan's against the
    least of the baselines'. No target: it tells the plan made before acting apart from
    what the disturbances cost."""
    if p.rate == 0:
        return ""

    def above(q: Point) -> float | None:
        calm = keyed.get((q.scenario, q.method, 0.0))
        return None if calm is None else q.planning_ms.value - calm.planning_ms.value

    mine = above(p)
    theirs = [a for a in (above(b) for b in base) if a is not None]
    if mine is None or not theirs:
        return ""
    best = min(theirs)
    if mine < 0.01:  # within the noise of the two medians: reacting cost nothing measurable
        return f"{mine:.2f} vs {best:.2f} (btplan: none)"
    return f"{mine:.2f} vs {best:.2f} ({best / mine:.1f}x)"


def explain_failures(rows: Sequence[Row], jobs: int = 1,
                     cache: Path | None = None) -> list[tuple[str, ...]]:
    """Every failed run by cause (btplan.sweep.explain), per scenario, rate and method.

    Rows from `btplan sweep` carry their cause. Rows written before the sweep named
    causes are explained here the same way, by rerunning their seeds with
    replan-unlimited; those reruns are kept in `cache` for the next report.
    """
    labelled = [dict(r) for r in rows]
    old = [r for r in labelled if explain.failed(r) and not r.get("cause")]
    known = read_rows(str(cache)) if cache is not None and cache.exists() else []
    verdict = {(r["scenario"], float(r["rate"]), int(r["seed"])): r for r in known}
    for case in CASES:
        needed = sorted({(float(r["rate"]), int(r["seed"])) for r in old
                         if r["scenario"] == case.scenario}
                        - {(rate, seed) for (sc, rate, seed) in verdict if sc == case.scenario})
        if not needed:
            continue
        job = Job(tuple(str(ROOT / f) for f in case.files), case.scenario)
        runs = [(explain.REFERENCE, rate, seed) for rate, seed in needed]
        found: list[Row] = []
        if jobs > 1:
            pool.run_local(job, runs, found.append, jobs)
        else:
            pool.run_serial(job, runs, found.append)
        verdict.update({(case.scenario, float(r["rate"]), int(r["seed"])): r for r in found})
        known += found
    if cache is not None and known:
        write_rows(str(cache), known)
    for scenario in {r["scenario"] for r in old}:
        mine = [r for r in old if r["scenario"] == scenario]
        explain.label(mine, {(rate, seed): r for (sc, rate, seed), r in verdict.items()
                             if sc == scenario})
    out: list[tuple[str, ...]] = [
        (scenario, f"{rate:g}", method, str(total), *(str(counts[c]) for c in explain.CAUSES))
        for scenario, method, rate, total, counts in explain.tally(labelled)]
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
            _table(("scenario", "rate", "planning ms: btplan vs best", "lower by",
                    "with set-up", "lower by", "success", "ticks to goal",
                    "reacting ms: above p = 0, btplan vs best"),
                   verdicts(points, rows)),
            "\n### Failed runs\n\n"]
    failures = explain_failures(rows, jobs, cache)
    if failures:
        text.append(_table(("scenario", "rate", "method", "failed runs",
                            *explain.CAUSES), failures))
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
    for path in sorted([*folder.glob("*.parquet"), *folder.glob("*.csv")]):  # not parts/
        for row in read_rows(str(path)):
            found[(row["scenario"], row["method"], float(row["rate"]), int(row["seed"]))] = row
    return list(found.values())


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--sweep", action="store_true", help="run the sweeps first")
    parser.add_argument("--seeds", type=int, default=1000, help="sweep seeds below this")
    parser.add_argument("--first", type=int, default=0, help="the first seed to sweep")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--scenarios", default=",".join(c.scenario for c in CASES),
                        help="which scenarios to sweep (comma-separated)")
    args = parser.parse_args(argv)
    if args.sweep:
        sweep(args.seeds, args.jobs, args.scenarios.split(","), args.first)
    rows = load_rows(RESULTS)
    if not rows:
        print("no rows in bench/results/: run with --sweep first", file=sys.stderr)
        return 1
    block = report(rows, args.jobs, RESULTS / "unlimited" / "reruns.parquet")
    sys.stdout.write(block)
    fill(PAGE, block)
    plot(summarize(rows), str(PLOT))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
