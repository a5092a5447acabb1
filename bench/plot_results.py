"""The plots of the results pages (docs/results/), drawn from the recorded outputs.

Each benchmark writes a plain-text table to bench/results/ (what the script printed,
after a `$ python bench/...` line). The pages show those numbers as tables; a plot is
added where they form a series: memory and speed against run length (soak), time and
memory against problem width (limits), the cost of each monitor and the time to show a
tree (monitor, browser view), a slow failing skill under each preset (acting
halts), and each BTPG goal's time beside the fastest BT planner's (btpg). Drawing from the recorded files, not from new runs, keeps a plot and the table
beside it the same measurement.

    python bench/plot_results.py            # every plot, into docs/images/results-*.png
    python bench/plot_results.py soak limits
"""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Callable
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results"
IMAGES = ROOT / "docs" / "images"


def lines_of(name: str) -> list[str]:
    return (RESULTS / name).read_text(encoding="utf-8").splitlines()


def numbers(line: str) -> list[float]:
    """The numbers of a table line, in order (signs and decimals kept)."""
    return [float(x) for x in re.findall(r"[-+]?\d+(?:\.\d+)?", line)]


def first_block(lines: list[str]) -> list[str]:
    """The output of the first command of a file that records several."""
    starts = [i for i, line in enumerate(lines) if line.startswith("$ ")]
    end = starts[1] if len(starts) > 1 else len(lines)
    return lines[:end]


# --- soak ------------------------------------------------------------------------------


def soak(fig: Figure) -> None:
    """Peak memory and ticks per second against the length of one run (trace off, on)."""
    rows: dict[bool, list[tuple[float, float, float]]] = {False: [], True: []}
    for line in first_block(lines_of("soak.txt")):
        m = re.match(r"\s*(\d+)\s+(yes|no)\s+\|", line)
        if m:
            n = numbers(line)  # ticks, before, at N/10, end, peak, ticks/s, seconds, ...
            rows[m.group(2) == "yes"].append((n[0], n[4], n[5]))
    memory, speed = fig.subplots(1, 2)
    for traced, points in rows.items():
        label = "with --trace" if traced else "no trace"
        ticks = [p[0] for p in points]
        memory.plot(ticks, [p[1] for p in points], marker="o", label=label)
        speed.plot(ticks, [p[2] for p in points], marker="o", label=label)
    style(memory, "peak resident memory (MB)", "ticks in the run", log_x=True)
    memory.set_ylim(bottom=0)
    style(speed, "ticks per second", "ticks in the run", log_x=True)
    speed.set_ylim(bottom=0)


# --- limits ----------------------------------------------------------------------------


def limits(fig: Figure) -> None:
    """Wall seconds and peak memory of both planners against the number of balls."""
    rows = [numbers(line.replace("kill", "-1")) for line in lines_of("limits.txt")
            if re.match(r"\s*\d+ \|", line)]
    limit = float(re.search(r"--timeout (\d+(?:\.\d+)?) s", "\n".join(lines_of("limits.txt"))
                            ).group(1))  # type: ignore[union-attr]
    sizes = [r[0] for r in rows]
    seconds, memory = fig.subplots(1, 2)
    seconds.plot(sizes, [r[1] for r in rows], marker="o", label="btplan plan --timeout")
    seconds.plot(sizes, [r[5] for r in rows], marker="s", label="pyperplan (killed at the limit)")
    seconds.axhline(limit, color="grey", linestyle="--", linewidth=1, label="the limit")
    memory.plot(sizes, [r[4] for r in rows], marker="o", label="btplan")
    memory.plot(sizes, [r[7] for r in rows], marker="s", label="pyperplan")
    style(seconds, "wall seconds", "balls in room a", log_x=True)
    style(memory, "peak resident memory (MB)", "balls in room a", log_x=True, log_y=True)


# --- monitor and browser view ----------------------------------------------------------


def monitor(fig: Figure) -> None:
    """Ticks per second with each monitor, and the time to show a tree in the browser."""
    variants = [(line[:20].strip(), numbers(line[20:])) for line in lines_of("monitor.txt")
                if line.startswith(("plain", "--"))]
    shows = [numbers(line) for line in lines_of("browser_view.txt")
             if re.match(r"\s*\d+\s+\d+", line)]
    rate, show = fig.subplots(1, 2)
    names = [v[0] for v in variants]
    rate.barh(names, [v[1][0] for v in variants])
    rate.invert_yaxis()
    for y, (_, n) in enumerate(variants):
        rate.text(n[0], y, f" {n[2]:.2f}", va="center", fontsize=7)
    rate.set_xlim(0, 1.15 * max(v[1][0] for v in variants))
    style(rate, "", "ticks per second (at the bar: against plain)", legend=False)
    nodes = [s[0] for s in shows]
    show.plot(nodes, [s[1] for s in shows], marker="o", label="page, best")
    show.plot(nodes, [s[2] for s in shows], marker="o", linestyle=":", label="page, median")
    show.plot(nodes, [s[3] for s in shows], marker="s", label="wall clock, best")
    show.plot(nodes, [s[4] for s in shows], marker="s", linestyle=":", label="wall clock, median")
    style(show, "ms from asking for the page to every node drawn", "nodes in the tree")
    show.set_ylim(bottom=0)


# --- acting halts ----------------------------------------------------------------------


def acting_halts(fig: Figure) -> None:
    """The slow failing skill: ticks to the goal and halts, per preset and skill length."""
    rows: dict[str, list[tuple[float, float, bool, float]]] = {}
    for line in lines_of("acting_halts.txt"):
        m = re.match(r"\s*(\d+) (before|after): (\w+)\s+(\d+)\s+(yes|no)\s+(\d+)", line)
        if m:
            rows.setdefault(m.group(3), []).append(
                (float(m.group(1)), float(m.group(4)), m.group(5) == "yes", float(m.group(6))))
    ticks, halts = fig.subplots(1, 2)
    for preset, points in rows.items():
        xs = [p[0] for p in points]
        dashed = {"linestyle": "--", "markersize": 9} if preset == "paper" else {}
        line, = ticks.plot(xs, [p[1] for p in points], marker="o", label=preset, **dashed)
        missed = [p for p in points if not p[2]]
        ticks.scatter([p[0] for p in missed], [p[1] for p in missed], marker="x", s=80,
                      color=line.get_color(), zorder=3)
        halts.plot(xs, [p[3] for p in points], marker="o", label=preset, **dashed)
    style(ticks, "ticks (x: goal not reached by the limit)", "ticks each skill takes", log_y=True)
    style(halts, "actions halted", "ticks each skill takes")


def btpg(fig: Figure) -> None:
    """Each goal's time: btplan beside the fastest BTPG planner of that goal."""
    goals: list[tuple[float, float, str]] = []
    for line in lines_of("btpg_rw_single.txt"):
        m = re.match(r"\s*\d+ (\S+)\s+(OBTEA|HBTP|BTExpansion)\s+([\d.]+)\s+([\d.]+)\s", line)
        if m:
            goals.append((float(m.group(3)), float(m.group(4)), m.group(2)))
    ax = fig.subplots(1, 1)
    for planner in ("BTExpansion", "OBTEA", "HBTP"):
        mine = [g for g in goals if g[2] == planner]
        ax.scatter([g[0] for g in mine], [g[1] for g in mine], s=14,
                   label=f"goals where {planner} is the fastest BTPG planner")
    top = max(max(g[0], g[1]) for g in goals) * 1.5
    ax.plot([0.03, top], [0.03, top], color="grey", linewidth=0.8, label="equal time")
    style(ax, "btplan, ms (problem read + plan)", "the fastest BTPG planner, ms (process())",
          log_x=True, log_y=True)


# --- drawing ---------------------------------------------------------------------------


def style(ax: Axes, ylabel: str, xlabel: str | None, log_x: bool = False,
          log_y: bool = False, legend: bool = True) -> None:
    if log_x:
        ax.set_xscale("log")
    if log_y:
        ax.set_yscale("log")
    ax.set_ylabel(ylabel, fontsize=8)
    if xlabel:
        ax.set_xlabel(xlabel, fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(alpha=0.3)
    if legend:
        ax.legend(fontsize=7)


PLOTS: dict[str, tuple[str, Callable[[Figure], None]]] = {
    "soak": ("results-soak.png", soak),
    "limits": ("results-limits.png", limits),
    "monitor": ("results-monitor.png", monitor),
    "acting_halts": ("results-acting-halts.png", acting_halts),
    "btpg": ("results-btpg.png", btpg),
}


def draw(name: str) -> Path:
    file, painter = PLOTS[name]
    fig = plt.figure(figsize=(9, 3.4))
    try:
        painter(fig)
        fig.tight_layout()
        out = IMAGES / file
        fig.savefig(out, dpi=110, metadata={"Software": None})
    finally:
        plt.close(fig)
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("plots", nargs="*", metavar="PLOT",
                        help=f"which plots ({', '.join(PLOTS)}); all when none is named")
    args = parser.parse_args(argv)
    unknown = [name for name in args.plots if name not in PLOTS]
    if unknown:
        parser.error(f"no plot named {', '.join(unknown)} (plots: {', '.join(PLOTS)})")
    for name in args.plots or list(PLOTS):
        print(draw(name).relative_to(ROOT), file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
