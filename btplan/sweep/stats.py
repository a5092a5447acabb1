"""Summaries of sweep rows: medians with distribution-free 95% intervals, success rates.

Medians, not means: planning times have long tails (one slow replan dominates a mean).
The interval of a median comes from order statistics (the binomial argument), so it is
exact, needs no resampling and is the same on every run; success rates get a Wilson
interval.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from btplan.sweep.runs import Row

Z95 = 1.959964


@dataclass(frozen=True)
class Estimate:
    """A value with the low and high ends of its 95% interval; all NaN (`NAN`) when there was
    nothing to estimate."""
    value: float
    low: float
    high: float

    def text(self, scale: float = 1.0, digits: int = 1) -> str:
        """`value [low, high]` times `scale`, with `digits` decimals; "-" for an estimate of
        nothing, so that tables never show nan."""
        if math.isnan(self.value):
            return "-"
        v, lo, hi = (x * scale for x in (self.value, self.low, self.high))
        return f"{v:.{digits}f} [{lo:.{digits}f}, {hi:.{digits}f}]"


NAN = Estimate(math.nan, math.nan, math.nan)


def median_interval(values: Iterable[float]) -> Estimate:
    """The median and a >= 95% confidence interval between two order statistics."""
    xs = sorted(values)
    n = len(xs)
    if n == 0:
        return NAN
    mid = (xs[(n - 1) // 2] + xs[n // 2]) / 2
    lo, hi = _ranks(n)
    return Estimate(mid, xs[lo], xs[hi])


def _ranks(n: int) -> tuple[int, int]:
    """0-based ranks (j, k) with P(x_(j) <= median <= x_(k)) >= 0.95, as tight as possible."""
    if n < 6:
        return 0, n - 1  # too few runs for a 95% interval: the whole range
    if n > 1000:
        half = Z95 * math.sqrt(n) / 2
        return max(0, math.floor(n / 2 - half) - 1), min(n - 1, math.ceil(n / 2 + half))
    # P(B < j) for B ~ Binomial(n, 1/2), found by summing the pmf from the bottom.
    pmf = [math.comb(n, i) / 2 ** n for i in range(n + 1)]
    tail, j = 0.0, 0
    while tail + pmf[j] <= 0.025:
        tail += pmf[j]
        j += 1
    # coverage of [x_(j), x_(n-1-j)] (0-based) is 1 - 2 * P(B < j) >= 0.95
    return max(j - 1, 0), min(n - j, n - 1)


def wilson(successes: int, n: int) -> Estimate:
    """The success rate `successes / n` with its Wilson 95% interval, which stays within [0, 1]
    and does not shrink to a point at 0% or 100% as the normal one does; NAN when `n` is 0."""
    if n == 0:
        return NAN
    p = successes / n
    denominator = 1 + Z95 ** 2 / n
    centre = (p + Z95 ** 2 / (2 * n)) / denominator
    half = Z95 * math.sqrt(p * (1 - p) / n + Z95 ** 2 / (4 * n * n)) / denominator
    return Estimate(p, max(0.0, centre - half), min(1.0, centre + half))


@dataclass(frozen=True)
class Point:
    """One point of the grid: a scenario, a method and a rate, over its seeds."""

    scenario: str
    method: str
    rate: float
    runs: int
    errors: int
    success: Estimate
    ticks: Estimate
    planner_calls: Estimate
    planning_ms: Estimate
    checks: Estimate
    setup_ms: Estimate = NAN
    """Task set-up before acting (grounding, models); "-" for rows written without it."""


def summarize(rows: Sequence[Row]) -> list[Point]:
    """One Point per (scenario, method, rate); ticks over the runs that reached the goal."""
    groups: dict[tuple[str, str, float], list[Row]] = {}
    for row in rows:
        groups.setdefault((row["scenario"], row["method"], float(row["rate"])), []).append(row)
    points = []
    for (scenario, method, rate), group in sorted(groups.items()):
        ok = [r for r in group if not r["error"]]
        good = [r for r in ok if r["success"]]
        points.append(Point(
            scenario, method, rate, len(group), len(group) - len(ok),
            wilson(len(good), len(ok)),
            median_interval(float(r["ticks"]) for r in good),
            median_interval(float(r["planner_calls"]) for r in ok),
            median_interval(1000 * float(r["planning_seconds"]) for r in ok),
            median_interval(float(r["checks"]) for r in ok),
            median_interval(1000 * float(r["setup_seconds"]) for r in ok
                            if r.get("setup_seconds") is not None),
        ))
    return points
