"""Generated problems of growing size, every planner as a whole process (bench/corpus.py).

For each domain the sizes run in order; a planner that fails (time limit, memory, no
plan) on a size is not run on the larger ones, so a domain is scaled until its peers
fail without spending the limit again and again. Each cell is wall time from process
start to exit, the validated plan length and the peak RSS (kernel, wait4).

    python bench/planning.py --scale blocksworld --sizes 10,20,40,70,100,200 --timeout 300
    python bench/planning.py --scale gripper,logistics --plot docs/images/scaling.png

Each run's points can be kept (`--save run.json`) and drawn together later, when the
domains need different time limits (`--replot a.json,b.json --plot docs/images/scaling.png`).
"""

from __future__ import annotations

import json
import statistics
import tempfile
from dataclasses import asdict, dataclass
from pathlib import Path

from corpus import Run, available, cell, run_one

from btplan.lang.generators import generate

SIZES = {
    "blocksworld": [10, 20, 30, 40, 50, 70, 100, 150, 200],
    "gripper": [10, 20, 40, 60, 80, 100, 150, 200],
    "logistics": [5, 10, 15, 20, 30, 40, 60],
}
SIZE_WORD = {"blocksworld": "blocks", "gripper": "balls", "logistics": "packages"}


@dataclass
class Point:
    domain: str
    size: int
    runs: dict[str, Run]


def scale(domains: list[str], sizes: dict[str, list[int]], planners: list[str], limit: float,
          seed: int = 0) -> list[Point]:
    planners = available(planners)
    points: list[Point] = []
    with tempfile.TemporaryDirectory() as folder:
        for name in domains:
            given_up: set[str] = set()
            for size in sizes[name]:
                domain_text, problem_text = generate(
                    name, "pddl", seed=seed, **{SIZE_WORD[name]: size})
                domain = Path(folder) / f"{name}-domain.pddl"
                problem = Path(folder) / f"{name}-{size}.pddl"
                domain.write_text(domain_text)
                problem.write_text(problem_text)
                runs = {p: run_one(p, domain, problem, limit)
                        for p in planners if p not in given_up}
                given_up |= {p for p, r in runs.items() if not r.solved}
                points.append(Point(name, size, runs))
                print(f"{name:<12} {size:>4} " + " | ".join(
                    f"{p}: {cell(r)}" for p, r in runs.items()), flush=True)
    return points


def save(points: list[Point], path: str) -> None:
    """The points as JSON, to be drawn with others (`load_points`)."""
    Path(path).write_text(json.dumps([asdict(p) for p in points], indent=1))


def load_points(paths: list[str]) -> list[Point]:
    """Points saved by `save`, from every file in turn."""
    points: list[Point] = []
    for path in paths:
        for item in json.loads(Path(path).read_text()):
            runs = {name: Run(**run) for name, run in item["runs"].items()}
            points.append(Point(item["domain"], item["size"], runs))
    return points


def report(points: list[Point], planners: list[str], limit: float) -> list[str]:
    lines = [f"largest size solved within {limit:g} s (and its time, plan length, peak RSS):"]
    for name in sorted({p.domain for p in points}):
        mine = [p for p in points if p.domain == name]
        parts = []
        for planner in planners:
            solved = [p for p in mine if planner in p.runs and p.runs[planner].solved]
            if not solved:
                parts.append(f"{planner} none")
                continue
            top = solved[-1]
            run = top.runs[planner]
            parts.append(f"{planner} {top.size} ({run.seconds:.1f} s, {run.length}, "
                         f"{run.rss_mb:.0f} MB)")
        lines.append(f"{name:<12} " + "; ".join(parts))
    rss = {pl: max((p.runs[pl].rss_mb for p in points if pl in p.runs), default=0.0)
           for pl in planners}
    lines.append("peak RSS over all runs: " + ", ".join(f"{p} {v:.0f} MB" for p, v in rss.items()))
    for peer in planners:
        if peer == "btplan":
            continue
        both = [p for p in points if all(x in p.runs and p.runs[x].solved
                                         for x in ("btplan", peer))]
        if both:
            ratio = statistics.median(p.runs["btplan"].seconds / p.runs[peer].seconds for p in both)
            length = statistics.median((p.runs["btplan"].length or 0)
                                       / max(p.runs[peer].length or 1, 1) for p in both)
            lines.append(f"btplan / {peer} on the {len(both)} sizes both solve: median time "
                         f"ratio {ratio:.2f}, median plan length ratio {length:.2f}")
    return lines


def plot(points: list[Point], planners: list[str], path: str) -> None:
    """Time (log scale) and plan length against size, one column per domain."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = sorted({p.domain for p in points})
    figure, axes = plt.subplots(2, len(names), figsize=(4.5 * len(names), 6.4), squeeze=False)
    labels = {"btplan": "btplan", "pyperplan": "pyperplan GBFS+hFF", "fd": "Fast Downward lama-first"}
    for column, name in enumerate(names):
        mine = [p for p in points if p.domain == name]
        for planner, marker in zip(planners, "osd^"):
            solved = [p for p in mine if planner in p.runs and p.runs[planner].solved]
            sizes = [p.size for p in solved]
            axes[0][column].plot(sizes, [p.runs[planner].seconds for p in solved],
                                 marker=marker, label=labels.get(planner, planner))
            axes[1][column].plot(sizes, [p.runs[planner].length or 0 for p in solved],
                                 marker=marker, label=labels.get(planner, planner))
        axes[0][column].set_yscale("log")
        axes[0][column].set_title(name)
        axes[0][column].set_ylabel("seconds, whole process")
        axes[1][column].set_ylabel("plan length")
        for axis in axes[:, column]:
            axis.set_xlabel(SIZE_WORD[name])
            axis.grid(True, alpha=0.3)
            axis.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(path, dpi=110, metadata={"Software": None})
    plt.close(figure)
