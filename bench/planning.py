"""Offline planning time of btplan beside pyperplan (GBFS with h_FF), in one process.

Both planners get the same generated PDDL files (btplan.lang.generators) and are
timed from the files to the answer: parsing, grounding and search for pyperplan;
parsing, backchaining and acting in the symbolic world for btplan. For every problem
the table shows whether each solved it, the seconds, the plan lengths (btplan's is
the list of actions its tree executed from the initial state), btplan's tree size
and the peak memory of each (tracemalloc, in a second, untimed run). btplan's plans
are validated against the domain before they count as solved.

    python bench/planning.py                        # default sizes, 2 seeds, 60 s limit
    python bench/planning.py --seeds 1 --timeout 20 --plot docs/images/planning_time.png
    python bench/planning.py --domains gripper --sizes 4,8,16
    python bench/planning.py --versus-paper         # btplan's defaults against Algorithms 1-3
                                                    # as published
                                                    # (docs/results/planner-versus-paper.md)
    python bench/planning.py --corpus DIR           # competition-layout domains, whole
                                                    # processes, beside peers (bench/corpus.py)
    python bench/planning.py --scale blocksworld --sizes 50,100,200 --timeout 300
                                                    # growing generated problems, whole
                                                    # processes, beside peers (bench/scaling.py)

Before timing whole processes (--corpus, --scale) the bench compiles btplan's bytecode
into its __pycache__ folders, as pip does when it installs a package: from an editable
checkout, with PYTHONDONTWRITEBYTECODE set, every btplan process would otherwise compile
its sources again, while pyperplan, installed by pip, loads bytecode. The run says so in
its first line.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import signal
import statistics
import tempfile
import time
import tracemalloc
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.errors import PlanningError
from btplan.lang.generators import GENERATORS, generate
from btplan.model import Task
from btplan.planner import PlannerOptions

DOMAINS = Path(__file__).resolve().parents[1] / "domains"

SIZES = {
    "blocksworld": [4, 6, 8, 10, 12, 15, 20, 25],
    "gripper": [2, 4, 8, 12, 16, 20, 30],
    "logistics": [1, 2, 3, 4, 6, 8, 10, 12],
}
SIZE_WORD = {"blocksworld": "blocks", "gripper": "balls", "logistics": "packages"}


@dataclass
class Outcome:
    solved: bool
    seconds: float
    length: int | None = None
    tree_size: int | None = None
    peak_mb: float | None = None
    note: str = ""


@dataclass
class Row:
    domain: str
    size: int
    seed: int
    btplan: Outcome
    pyperplan: Outcome


class Timeout(Exception):
    pass


@contextlib.contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Interrupt the block after `seconds` (SIGALRM: main thread, Unix only)."""

    def stop(signum: int, frame: object) -> None:
        raise Timeout

    previous = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def valid(task: Task, actions: list) -> bool:  # type: ignore[type-arg]
    state = task.initial_state
    for action in actions:
        if not action.applicable(state):
            return False
        state = action.apply(state)
    return all(g.holds(state) for g in task.goal_literals)


def run_btplan(domain: str, problem: str, limit: float) -> Outcome:
    start = time.perf_counter()
    try:
        with time_limit(limit):
            task = load(domain, problem)
            result = plan(task, timeout=limit)
    except (Timeout, PlanningError) as error:
        note = "timeout" if isinstance(error, Timeout) else error.reason[:60]
        return Outcome(False, time.perf_counter() - start, note=note)
    seconds = time.perf_counter() - start
    if not valid(task, result.executed):
        return Outcome(False, seconds, note="invalid plan")
    return Outcome(True, seconds, len(result.executed), result.stats.tree_size)


def run_pyperplan(domain: str, problem: str, limit: float) -> Outcome:
    import logging

    from pyperplan.planner import HEURISTICS, SEARCHES, search_plan

    logging.disable(logging.CRITICAL)  # pyperplan logs every step at INFO
    start = time.perf_counter()
    try:
        with time_limit(limit):
            solution = search_plan(domain, problem, SEARCHES["gbf"], HEURISTICS["hff"])
    except Timeout:
        return Outcome(False, time.perf_counter() - start, note="timeout")
    seconds = time.perf_counter() - start
    if solution is None:
        return Outcome(False, seconds, note="no plan")
    return Outcome(True, seconds, len(solution))


def peak_mb(run: Callable[[str, str, float], Outcome], domain: str, problem: str,
            limit: float) -> float:
    tracemalloc.start()
    try:
        run(domain, problem, limit)
        return tracemalloc.get_traced_memory()[1] / 1e6
    finally:
        tracemalloc.stop()


def bench(domains: list[str], sizes: dict[str, list[int]], seeds: int, limit: float,
          memory: bool) -> list[Row]:
    rows: list[Row] = []
    with tempfile.TemporaryDirectory() as folder:
        for name in domains:
            for size in sizes[name]:
                for seed in range(seeds):
                    domain_text, problem_text = generate(
                        name, "pddl", seed=seed, **{SIZE_WORD[name]: size})
                    domain = os.path.join(folder, f"{name}-domain.pddl")
                    problem = os.path.join(folder, f"{name}-{size}-{seed}.pddl")
                    Path(domain).write_text(domain_text)
                    Path(problem).write_text(problem_text)
                    ours = run_btplan(domain, problem, limit)
                    theirs = run_pyperplan(domain, problem, limit)
                    if memory and ours.solved and ours.seconds < limit / 4:
                        ours.peak_mb = peak_mb(run_btplan, domain, problem, limit)
                    if memory and theirs.solved and theirs.seconds < limit / 4:
                        theirs.peak_mb = peak_mb(run_pyperplan, domain, problem, limit)
                    row = Row(name, size, seed, ours, theirs)
                    print(line(row), flush=True)
                    rows.append(row)
    return rows


def cell(outcome: Outcome) -> str:
    if not outcome.solved:
        return f"{'-':>8} {outcome.seconds:7.2f}s {outcome.note[:18]:<18}"
    memory = f"{outcome.peak_mb:6.1f}MB" if outcome.peak_mb is not None else f"{'':8}"
    return f"{outcome.length:>8} {outcome.seconds:7.2f}s {memory:<18}"


def line(row: Row) -> str:
    tree = row.btplan.tree_size if row.btplan.tree_size is not None else "-"
    return (f"{row.domain:<12} {row.size:>4} {row.seed:>4} | {cell(row.btplan)} tree {tree!s:>5}"
            f" | {cell(row.pyperplan)}")


def summary(rows: list[Row], limit: float) -> list[str]:
    out: list[str] = []
    for name in sorted({r.domain for r in rows}):
        mine = [r for r in rows if r.domain == name]
        ours = [r.btplan.seconds for r in mine if r.btplan.solved]
        theirs = [r.pyperplan.seconds for r in mine if r.pyperplan.solved]
        both = [r for r in mine if r.btplan.solved and r.pyperplan.solved]
        missed = [f"{r.size}/{r.seed}" for r in mine if r.pyperplan.solved and not r.btplan.solved]
        ratio = (statistics.median(r.btplan.length / max(r.pyperplan.length, 1) for r in both)
                 if both else float("nan"))
        out.append(
            f"{name:<12} solved btplan {len(ours)}/{len(mine)}, pyperplan {len(theirs)}/{len(mine)}"
            f" (limit {limit:g} s); median s btplan "
            f"{statistics.median(ours) if ours else float('nan'):.3f}, pyperplan "
            f"{statistics.median(theirs) if theirs else float('nan'):.3f}; median plan length "
            f"ratio btplan/pyperplan {ratio:.2f}"
            + (f"; pyperplan-only solves: {', '.join(missed)}" if missed else ""))
    return out


def plot(rows: list[Row], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = sorted({r.domain for r in rows})
    figure, axes = plt.subplots(1, len(names), figsize=(4.5 * len(names), 3.6), squeeze=False)
    for axis, name in zip(axes[0], names):
        mine = [r for r in rows if r.domain == name]
        for label, pick, marker in (("btplan", lambda r: r.btplan, "o"),
                                    ("pyperplan GBFS+hFF", lambda r: r.pyperplan, "s")):
            sizes = sorted({r.size for r in mine})
            medians = []
            for size in sizes:
                times = [pick(r).seconds for r in mine if r.size == size and pick(r).solved]
                medians.append(statistics.median(times) if times else float("nan"))
            axis.plot(sizes, medians, marker=marker, label=label)
        axis.set_yscale("log")
        axis.set_title(name)
        axis.set_xlabel(SIZE_WORD[name])
        axis.set_ylabel("seconds (median over seeds)")
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=110, metadata={"Software": None})
    plt.close(figure)


def versus_paper(limit: float) -> None:
    """Solved counts and outcomes of the published algorithms beside btplan's defaults."""
    cases = [("blocksworld", n, s) for n in (4, 6, 8, 10) for s in range(5)]
    cases += [("gripper", n, s) for n in (2, 4, 8) for s in range(3)]
    cases += [("logistics", n, s) for n in (1, 2, 4) for s in range(3)]
    for mode, options in (("paper", PlannerOptions.paper()), ("btplan", None)):
        start = time.perf_counter()
        counts: dict[str, dict[str, int]] = {}
        for name, size, seed in cases:
            domain, problem = GENERATORS[name](size, seed=seed)
            task = Task(domain=domain, problem=problem)
            try:
                plan(task, options=options, timeout=limit)
                outcome = "solved"
            except PlanningError as error:
                outcome = type(error).__name__
            counts.setdefault(name, {}).setdefault(outcome, 0)
            counts[name][outcome] += 1
        for path in ("planner_sussman.bt", "planner_invert.bt", "planner_swap.bt"):
            try:
                plan(load(str(DOMAINS / path)), options=options, timeout=limit)
                outcome = "solved"
            except PlanningError as error:
                outcome = type(error).__name__
            counts[path] = {outcome: 1}
        print(f"{mode:<7} {time.perf_counter() - start:6.1f}s  " + "; ".join(
            f"{name}: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items()))
            for name, c in counts.items()))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--domains", default="blocksworld,gripper,logistics")
    parser.add_argument("--sizes", help="comma-separated sizes, for every chosen domain")
    parser.add_argument("--seeds", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=60.0)
    parser.add_argument("--no-memory", action="store_true", help="skip the tracemalloc runs")
    parser.add_argument("--plot", help="write a PNG of time against size here")
    parser.add_argument("--versus-paper", action="store_true",
                        help="compare with Algorithms 1-3 as published instead")
    parser.add_argument("--corpus", help="a folder of competition-layout domain folders")
    parser.add_argument("--per-domain", type=int, default=3,
                        help="with --corpus: the N smallest problems of each domain")
    parser.add_argument("--planners", default="btplan,pyperplan,fd",
                        help="with --corpus or --scale: planners to run (fd needs the 'fd' "
                             "extra)")
    parser.add_argument("--only", help="with --corpus: comma-separated domain folders")
    parser.add_argument("--fd-python", metavar="PYTHON",
                        help="with --corpus or --scale: run Fast Downward with this "
                             "interpreter (one whose environment has up-fast-downward)")
    parser.add_argument("--scale", metavar="DOMAINS",
                        help="comma-separated generated domains, grown until a planner fails, "
                             "each planner a whole process (--planners, --sizes, --plot)")
    parser.add_argument("--save", help="with --scale: keep the points as JSON here")
    parser.add_argument("--replot", metavar="FILES",
                        help="comma-separated JSON files of --save: report and --plot them")
    args = parser.parse_args()
    if args.fd_python:
        import corpus

        corpus.FD_PYTHON = args.fd_python
    if args.scale or args.replot:
        import scaling

        planners = args.planners.split(",")
        if args.replot:
            points = scaling.load_points(args.replot.split(","))
        else:
            names = args.scale.split(",")
            sizes = dict(scaling.SIZES)
            if args.sizes:
                sizes.update({d: [int(x) for x in args.sizes.split(",")] for d in names})
            points = scaling.scale(names, sizes, planners, args.timeout)
            if args.save:
                scaling.save(points, args.save)
        print()
        print("\n".join(scaling.report(points, planners, args.timeout)))
        if args.plot:
            scaling.plot(points, planners, args.plot)
            print(f"plot: {args.plot}")
        return
    if args.corpus:
        from corpus import bench_corpus, report

        planners = args.planners.split(",")
        cases = bench_corpus(Path(args.corpus), planners, args.per_domain, args.timeout,
                             args.only.split(",") if args.only else None)
        print()
        print("\n".join(report(cases, planners, args.timeout)))
        return
    if args.versus_paper:
        versus_paper(min(args.timeout, 10.0))
        return
    domains = args.domains.split(",")
    sizes = dict(SIZES)
    if args.sizes:
        sizes.update({d: [int(x) for x in args.sizes.split(",")] for d in domains})
    print(f"{'domain':<12} {'size':>4} {'seed':>4} | {'btplan: len, time, memory':<36} tree"
          f"  | pyperplan GBFS+hFF: len, time, memory")
    rows = bench(domains, sizes, args.seeds, args.timeout, not args.no_memory)
    print()
    for text in summary(rows, args.timeout):
        print(text)
    if args.plot:
        plot(rows, args.plot)
        print(f"plot: {args.plot}")


if __name__ == "__main__":
    main()
