"""Two-armed assembly of k parts: btplan beside pyperplan (GBFS with h_FF), in one process.

The paper's Yumi scenario is about scale: long plans with regrasp and handover chains
found by backchaining. For k = 4 ... 64 generated parts (`btplan generate assembly`),
both planners get the same PDDL files and are timed from the files to the answer.
btplan's numbers are those of its offline planning, which acts in the symbolic world:
the actions the tree executed from the initial state, the tree's size and the number
of expansions. The shortest plan is known without search (a pick and an insert per
part, and one handover per part lying opening down), so both lengths are also shown
against it. Plans of both planners are validated against the domain.

    python bench/assembly.py                                  # k = 4..64, 2 seeds, 300 s
    python bench/assembly.py --sizes 4,8 --seeds 1 --timeout 20
    python bench/assembly.py --plot docs/assembly.png
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from planning import Outcome, Timeout, run_pyperplan, time_limit, valid

from btplan.acting.offline import load, plan
from btplan.errors import PlanningError
from btplan.lang.assembly import assembly
from btplan.lang.generators import render

SIZES = [4, 8, 16, 32, 64]


@dataclass
class Row:
    parts: int
    seed: int
    shortest: int
    btplan: Outcome
    expansions: int | None
    pyperplan: Outcome


def run_btplan(domain: str, problem: str, limit: float) -> tuple[Outcome, int | None]:
    start = time.perf_counter()
    try:
        with time_limit(limit):
            task = load(domain, problem)
            result = plan(task, timeout=limit)
    except (Timeout, PlanningError) as error:
        note = "timeout" if isinstance(error, Timeout) else error.reason[:60]
        return Outcome(False, time.perf_counter() - start, note=note), None
    seconds = time.perf_counter() - start
    if not valid(task, result.executed):
        return Outcome(False, seconds, note="invalid plan"), None
    outcome = Outcome(True, seconds, len(result.executed), result.stats.tree_size)
    return outcome, result.stats.expansions


def bench(sizes: list[int], seeds: int, limit: float) -> list[Row]:
    rows: list[Row] = []
    with tempfile.TemporaryDirectory() as folder:
        # One untimed run each first, so that no timed run pays for imports and parsers.
        warm_domain, warm_problem = render(*assembly(2, 0), "pddl")
        Path(folder, "warm-domain.pddl").write_text(warm_domain)
        Path(folder, "warm-problem.pddl").write_text(warm_problem)
        run_btplan(os.path.join(folder, "warm-domain.pddl"),
                   os.path.join(folder, "warm-problem.pddl"), limit)
        run_pyperplan(os.path.join(folder, "warm-domain.pddl"),
                      os.path.join(folder, "warm-problem.pddl"), limit)
        for parts in sizes:
            for seed in range(seeds):
                domain_model, problem_model = assembly(parts, seed)
                domain_text, problem_text = render(domain_model, problem_model, "pddl")
                domain = os.path.join(folder, "assembly-domain.pddl")
                problem = os.path.join(folder, f"assembly-{parts}-{seed}.pddl")
                Path(domain).write_text(domain_text)
                Path(problem).write_text(problem_text)
                down = sum(1 for f in problem_model.init
                           if f.predicate == "lies" and f.args[2] == "down")
                ours, expansions = run_btplan(domain, problem, limit)
                theirs = run_pyperplan(domain, problem, limit)
                row = Row(parts, seed, 2 * parts + down, ours, expansions, theirs)
                print(line(row), flush=True)
                rows.append(row)
    return rows


def cell(outcome: Outcome) -> str:
    if not outcome.solved:
        return f"{'-':>6} {outcome.seconds:8.2f}s {outcome.note[:10]:<10}"
    return f"{outcome.length:>6} {outcome.seconds:8.2f}s {'':<10}"


def line(row: Row) -> str:
    tree = row.btplan.tree_size if row.btplan.tree_size is not None else "-"
    return (f"{row.parts:>4} {row.seed:>4} {row.shortest:>8} | {cell(row.btplan)} tree {tree!s:>5}"
            f" exp {row.expansions!s:>4} | {cell(row.pyperplan)}")


def slope(rows: list[Row], pick: str) -> float:
    """Least-squares slope of log(seconds) on log(k): the exponent of the growth."""
    points = [(math.log(r.parts), math.log(getattr(r, pick).seconds))
              for r in rows if getattr(r, pick).solved]
    if len({x for x, _ in points}) < 2:
        return float("nan")
    mx = statistics.fmean(x for x, _ in points)
    my = statistics.fmean(y for _, y in points)
    return (sum((x - mx) * (y - my) for x, y in points)
            / sum((x - mx) ** 2 for x, _ in points))


def summary(rows: list[Row], limit: float) -> list[str]:
    both = [r for r in rows if r.btplan.solved and r.pyperplan.solved]
    ours = [r for r in rows if r.btplan.solved]
    out = [
        f"solved btplan {len(ours)}/{len(rows)}, pyperplan "
        f"{sum(r.pyperplan.solved for r in rows)}/{len(rows)} (limit {limit:g} s)",
        "executed actions / pyperplan plan length: "
        + (", ".join(f"k={r.parts}/s{r.seed} {r.btplan.length / r.pyperplan.length:.2f}"
                     for r in both) or "no problem solved by both"),
        "executed actions / shortest plan: "
        + (f"max {max(r.btplan.length / r.shortest for r in ours):.2f}" if ours else "-"),
        f"growth exponent of time in k (log-log slope): btplan {slope(rows, 'btplan'):.2f}, "
        f"pyperplan {slope(rows, 'pyperplan'):.2f} (over the sizes each solved)",
    ]
    return out


def plot(rows: list[Row], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sizes = sorted({r.parts for r in rows})

    def median(values: list[float]) -> float:
        return statistics.median(values) if values else float("nan")

    figure, (left, right) = plt.subplots(1, 2, figsize=(9.5, 3.8))
    for label, pick, marker in (("btplan", "btplan", "o"), ("pyperplan GBFS+hFF", "pyperplan", "s")):
        seconds = [median([getattr(r, pick).seconds for r in rows
                           if r.parts == k and getattr(r, pick).solved]) for k in sizes]
        length = [median([float(getattr(r, pick).length) for r in rows
                          if r.parts == k and getattr(r, pick).solved]) for k in sizes]
        left.plot(sizes, seconds, marker=marker, label=label)
        right.plot(sizes, length, marker=marker, label=label)
    right.plot(sizes, [median([float(r.shortest) for r in rows if r.parts == k]) for k in sizes],
               linestyle="--", color="grey", label="shortest")
    left.set_xscale("log", base=2)
    left.set_yscale("log")
    left.set_ylabel("planning seconds (median over seeds)")
    right.set_xscale("log", base=2)
    right.set_yscale("log")
    right.set_ylabel("plan length (median over seeds)")
    for axis in (left, right):
        axis.set_xlabel("parts k")
        axis.set_xticks(sizes, [str(k) for k in sizes])
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110, metadata={"Software": None})
    plt.close(figure)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)),
                        help="comma-separated part counts")
    parser.add_argument("--seeds", type=int, default=2, help="seeds 0..N-1 per size")
    parser.add_argument("--timeout", type=float, default=300.0, help="seconds per planner run")
    parser.add_argument("--plot", help="write a PNG of time and plan length against k")
    args = parser.parse_args()
    sizes = [int(s) for s in args.sizes.split(",")]
    print("   k seed shortest | btplan: len, time, tree size, expansions"
          " | pyperplan GBFS+hFF: len, time")
    rows = bench(sizes, args.seeds, args.timeout)
    for text in summary(rows, args.timeout):
        print(text)
    if args.plot:
        plot(rows, args.plot)


if __name__ == "__main__":
    main()
