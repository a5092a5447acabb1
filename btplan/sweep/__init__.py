"""Sweeps: many seeded runs of several methods over a grid of disturbance rates.

`scenarios` names the agents of a run, `runs` computes one row, `pool` spreads the
runs over local processes or a Ray cluster, `stats` summarises the rows with
intervals and `output` writes them (CSV, Parquet) and draws them.
"""

from btplan.sweep.runs import COLUMNS, METHODS, Job, run_one
from btplan.sweep.scenarios import BUILTIN, Scenario, resolve

__all__ = ["BUILTIN", "COLUMNS", "METHODS", "Job", "Scenario", "resolve", "run_one"]
