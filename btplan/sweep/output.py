"""Sweep results on disk and on screen: rows as CSV or Parquet, a summary table, a plot.

The file format follows the extension. Rows are sorted by their name (scenario,
method, rate, seed), so the same sweep writes the same file whichever worker finished
first; files are written whole or not at all.
"""

from __future__ import annotations

import csv
import importlib.util
import io
import math
from collections.abc import Sequence
from pathlib import Path

from btplan.errors import InputError, MissingExtraError, Span
from btplan.io import write_atomic, write_bytes_atomic
from btplan.sweep.runs import COLUMNS, Row
from btplan.sweep.stats import Estimate, Point

FORMATS = (".csv", ".parquet")
PLOT_FORMATS = (".png", ".svg", ".pdf")
MATPLOTLIB_MISSING = "--plot needs matplotlib: pip install 'btplan[bench]'"


def check_output(path: str) -> None:
    """Refuse an output we could not write, before hours of runs rather than after."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise InputError(f"cannot tell the format of '{path}'", Span("--output", 1, 1),
                         "name it .csv or .parquet")
    folder = Path(path).parent
    if str(folder) and not folder.is_dir():
        raise InputError("the folder for this output does not exist", Span(path, 1, 1))
    if suffix == ".parquet":
        _pyarrow()


def check_plot(path: str) -> None:
    """Refuse a plot we could not draw, before the runs: the rows would be written, but
    the plot asked for would be lost to a format or a package found missing at the end."""
    if Path(path).suffix.lower() not in PLOT_FORMATS:
        raise InputError(f"cannot tell the image format of '{path}'", Span("--plot", 1, 1),
                         "name it .png, .svg or .pdf")
    if importlib.util.find_spec("matplotlib") is None:
        raise MissingExtraError(MATPLOTLIB_MISSING)


def _pyarrow() -> None:
    try:
        import pyarrow  # type: ignore[import-untyped]  # noqa: F401
    except ImportError:
        raise MissingExtraError("Parquet output needs pyarrow: pip install 'btplan[parquet]' "
                                "(or write .csv)") from None


def sort_rows(rows: Sequence[Row]) -> list[Row]:
    """The rows by scenario, method, rate and seed (numbers compared as numbers), so that the
    output is the same in whatever order the parallel runs finished."""
    return sorted(rows, key=lambda r: (r["scenario"], r["method"], float(r["rate"]),
                                       int(r["seed"])))


def write_rows(path: str, rows: Sequence[Row]) -> None:
    """Write the rows, sorted, to `path` at once: Parquet for .parquet, else CSV with every
    one of COLUMNS (empty where older rows lack a newer column)."""
    ordered = sort_rows(rows)
    if Path(path).suffix.lower() == ".parquet":
        _write_parquet(path, ordered)
        return
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in ordered:
        writer.writerow({k: row.get(k) for k in COLUMNS})  # older rows lack newer columns
    write_atomic(path, buffer.getvalue())


def _write_parquet(path: str, rows: Sequence[Row]) -> None:
    _pyarrow()
    import pyarrow as pa
    import pyarrow.parquet as pq  # type: ignore[import-untyped]

    table = pa.Table.from_pylist([{k: r.get(k) for k in COLUMNS} for r in rows])
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    write_bytes_atomic(path, sink.getvalue().to_pybytes())  # whole, with the usual mode


def read_rows(path: str) -> list[Row]:
    """Rows written by write_rows, with their types back (for reports and tests)."""
    if Path(path).suffix.lower() == ".parquet":
        _pyarrow()
        import pyarrow.parquet as pq

        return [dict(r) for r in pq.read_table(path).to_pylist()]
    with open(path, encoding="utf-8", newline="") as handle:
        out = []
        for r in csv.DictReader(handle):
            out.append({
                "scenario": r["scenario"], "method": r["method"], "rate": float(r["rate"]),
                "seed": int(r["seed"]), "success": r["success"] == "True",
                "ticks": int(r["ticks"]), "actions": int(r["actions"]),
                "planner_calls": int(r["planner_calls"]),
                "planning_seconds": float(r["planning_seconds"]),
                "setup_seconds": (float(r["setup_seconds"]) if r.get("setup_seconds")
                                  else None),
                "checks": float(r["checks"]), "disturbances": int(r["disturbances"]),
                "reason": r.get("reason") or "", "cause": r.get("cause") or "",
                "error": r["error"],
            })
        return out


HEADER = ("scenario", "method", "rate", "runs", "success", "ticks to goal",
          "planner calls", "planning ms (CPU)", "setup ms (CPU)", "checks/tick", "errors")


def table_cells(points: Sequence[Point]) -> list[tuple[str, ...]]:
    """The summary, one line per point: medians [95% interval], success as a percentage."""
    cells: list[tuple[str, ...]] = []
    for p in points:
        cells.append((p.scenario, p.method, f"{p.rate:g}", str(p.runs),
                      _percent(p.success),
                      p.ticks.text(digits=0), p.planner_calls.text(digits=0),
                      p.planning_ms.text(digits=2), p.setup_ms.text(digits=2),
                      p.checks.text(digits=1), str(p.errors)))
    return cells


def _percent(e: Estimate) -> str:
    if math.isnan(e.value):
        return "-"
    return f"{100 * e.value:.0f}% [{100 * e.low:.0f}%, {100 * e.high:.0f}%]"


def markdown_table(points: Sequence[Point]) -> str:
    """The summary as a Markdown table, numbers right-aligned: what a sweep prints when it
    ends, ready to paste into a report."""
    lines = ["| " + " | ".join(HEADER) + " |",
             "|---|---|" + "---:|" * (len(HEADER) - 2)]
    lines += ["| " + " | ".join(c) + " |" for c in table_cells(points)]
    return "\n".join(lines) + "\n"


def plot(points: Sequence[Point], path: str) -> None:
    """Success and planning CPU time against rate, one column per scenario, with intervals."""
    try:
        import matplotlib
    except ImportError:
        raise MissingExtraError(MATPLOTLIB_MISSING) from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenarios = sorted({p.scenario for p in points})
    metrics = (("success", "success rate"), ("planning_ms", "planning CPU ms (median)"),
               ("ticks", "ticks to goal (median)"))
    fig, axes = plt.subplots(len(metrics), len(scenarios),
                             figsize=(4.2 * len(scenarios), 3.0 * len(metrics)), squeeze=False)
    for j, scenario in enumerate(scenarios):
        for i, (field, label) in enumerate(metrics):
            ax = axes[i][j]
            for method in sorted({p.method for p in points if p.scenario == scenario}):
                pts = sorted((p for p in points if p.scenario == scenario and p.method == method),
                             key=lambda p: p.rate)
                est = [getattr(p, field) for p in pts]
                xs = [p.rate for p in pts]
                ax.plot(xs, [e.value for e in est], marker="o", label=method)
                ax.fill_between(xs, [e.low for e in est], [e.high for e in est], alpha=0.2)
            if field == "success":
                ax.set_ylim(-0.05, 1.05)
            if field == "planning_ms":
                ax.set_yscale("log")
            ax.set_title(f"{scenario}: {label}", fontsize=9)
            ax.set_xlabel("disturbance rate", fontsize=8)
            ax.grid(alpha=0.3)
            if i == 0:
                ax.legend(fontsize=7)
    fig.tight_layout()
    image = io.BytesIO()
    try:
        fig.savefig(image, dpi=110, format=Path(path).suffix.lower().lstrip("."))
    finally:
        plt.close(fig)
    write_bytes_atomic(path, image.getvalue())  # whole, with the usual mode
