"""Whole-process time of `btplan plan` beside pyperplan on small problems: start-up counts.

On problems either planner solves in milliseconds, what a user waits for is the
interpreter, the imports and reading the files. Each planner (and each other btplan
source tree given with --also, put first on PYTHONPATH) runs as its own process, in
turn, --runs times on each problem; the table gives medians of CPU (user + system,
from wait4) and wall seconds, and the median over the problems of each one's ratio to
pyperplan, with the load average before and after. Bytecode is compiled first for every
btplan tree, as pip does for an installed package (bench/corpus.py). Plans are not
validated here: `bench/planning.py --corpus` does that.

    python bench/startup.py --corpus DIR [--runs 3] [--also before=SRC]
                            [--problems tpp/p01,storage/p01]
"""

from __future__ import annotations

import argparse
import compileall
import os
import statistics
import tempfile
import time
from pathlib import Path

from corpus import command

SMALL = ("tpp/p01,tpp/p02,tpp/p03,storage/p01,storage/p02,storage/p03,mystery/p01,"
         "mystery/p09,pipesworld/p01,pipesworld/p03")
"""Ten small problems btplan and pyperplan both solve, in well under a second each."""


def timed(argv: list[str], env: dict[str, str]) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of one whole process; it must exit with 0."""
    start = time.perf_counter()
    pid = os.posix_spawn(argv[0], argv, env, file_actions=[
        (os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
        (os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0),
        (os.POSIX_SPAWN_OPEN, 2, os.devnull, os.O_WRONLY, 0)])
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"failed: {' '.join(argv)}")
    return usage.ru_utime + usage.ru_stime, wall


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--corpus", required=True, help="competition-layout domain folders")
    parser.add_argument("--problems", default=SMALL, help="comma-separated DOMAIN/PROBLEM")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--also", action="append", default=[], metavar="LABEL=SRC",
                        help="another btplan source tree (the folder holding btplan/)")
    args = parser.parse_args()
    trees = {"btplan": None, **dict(a.split("=", 1) for a in args.also)}
    import btplan

    for source in [str(Path(btplan.__file__).parents[1]), *filter(None, trees.values())]:
        compileall.compile_dir(str(Path(source) / "btplan"), quiet=1)
    print("btplan's bytecode compiled first (every tree), as pip compiles an installed package")
    labels = [*trees, "pyperplan"]
    cpu: dict[str, list[float]] = {x: [] for x in labels}
    wall: dict[str, list[float]] = {x: [] for x in labels}
    load = os.getloadavg()[0]
    corpus = Path(args.corpus).resolve()
    with tempfile.TemporaryDirectory() as work:
        os.chdir(work)  # `python -c` puts the working folder first on sys.path
        for name in args.problems.split(","):
            folder, stem = name.split("/")
            problem = corpus / folder / f"{stem}.pddl"
            domain = problem.with_name("domain.pddl")
            runs: dict[str, list[tuple[float, float]]] = {x: [] for x in labels}
            for _ in range(args.runs):  # in turn, so a change of load hits each alike
                for label in labels:
                    planner = "pyperplan" if label == "pyperplan" else "btplan"
                    env = dict(os.environ)
                    if trees.get(label):
                        env["PYTHONPATH"] = str(trees[label])
                    argv = command(planner, domain, problem, os.path.join(work, "plan"), 60)
                    runs[label].append(timed(argv, env))
            for label in labels:
                cpu[label].append(statistics.median(c for c, _ in runs[label]))
                wall[label].append(statistics.median(w for _, w in runs[label]))
            print(f"{name:<16} " + " | ".join(
                f"{x}: {cpu[x][-1]:.3f} s CPU, {wall[x][-1]:.3f} s wall" for x in labels),
                flush=True)
    print(f"load average (1 min): {load:.1f} before, {os.getloadavg()[0]:.1f} after")
    for label in labels[:-1]:
        c = statistics.median(a / b for a, b in zip(cpu[label], cpu["pyperplan"], strict=True))
        w = statistics.median(a / b for a, b in zip(wall[label], wall["pyperplan"], strict=True))
        print(f"{label} / pyperplan, median over the problems: CPU {c:.2f}, wall {w:.2f}")


if __name__ == "__main__":
    main()
