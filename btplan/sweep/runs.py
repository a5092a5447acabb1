"""One seeded run of one method: the unit of work a sweep hands to a worker.

A run is named by (method, rate, seed) within a `Job` (domain files, scenario, world),
and gives one row of plain values, so that any worker (a local process, a Ray task)
computes the same row for the same name. A run that raises becomes a row with the
error, never a missing row.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass
from typing import Any

from btplan import acting
from btplan.acting.config import ActingConfig
from btplan.baselines import BASELINES, run_baseline
from btplan.errors import BtplanError, InputError, Span
from btplan.model import Task
from btplan.robot.contract import capabilities_of
from btplan.sweep.scenarios import Scenario, resolve

METHODS = ("btplan", "btplan-paper", *BASELINES)

COLUMNS = ("scenario", "method", "rate", "seed", "success", "ticks", "actions",
           "planner_calls", "planning_seconds", "setup_seconds", "checks", "disturbances",
           "reason", "cause", "error")
"""One row per run; `checks` is condition checks per tick. `planning_seconds` is the CPU
time of the expansions or searches, `setup_seconds` that of what depends on the task
only (grounding, relaxed model, mutexes), built before acting. `reason` is how the run
ended; `cause`, for a failed run, names why (btplan.sweep.explain)."""

TIMED = ("planning_seconds", "setup_seconds")
"""Columns that vary between two runs of the same seed (everything else repeats)."""

Row = dict[str, Any]


@dataclass(frozen=True)
class Job:
    """What every run of a sweep shares; small and picklable, sent to each worker."""

    files: tuple[str, ...]
    scenario: str
    sim: str = "symbolic"
    max_ticks: int | None = None


@functools.lru_cache(maxsize=4)
def prepared(job: Job) -> tuple[Task, Scenario, int]:
    """The task as the scenario runs it, the scenario and the tick budget (once per worker)."""
    scenario = resolve(job.scenario)
    task = scenario.prepare(acting.load(*job.files))
    scenario.check(task)
    return task, scenario, job.max_ticks or scenario.max_ticks


def check_methods(methods: list[str], sim: str) -> None:
    """Every method is known; each runs in either world (the baselines ask the simulator
    for the trajectories and poses it refines: btplan.acting.refined)."""
    for method in methods:
        if method not in METHODS:
            raise InputError(f"unknown method '{method}'", Span("--method", 1, 1),
                             "one of " + ", ".join(METHODS))


def check_sim(job: Job) -> None:
    """Refuse a scenario whose agents the chosen world cannot serve, before any run."""
    resolve(job.scenario).check_sim(job.sim)


def empty_row(job: Job, method: str, rate: float, seed: int, error: str) -> Row:
    """The row of a run that measured nothing (it raised or timed out): zeros, no success,
    `error` saying why. The scenario's own text stands in when it cannot be resolved."""
    try:
        scenario = resolve(job.scenario).name
    except BtplanError:
        scenario = job.scenario
    return {"scenario": scenario, "method": method, "rate": rate, "seed": seed,
            "success": False, "ticks": 0, "actions": 0, "planner_calls": 0,
            "planning_seconds": 0.0, "setup_seconds": 0.0, "checks": 0.0, "disturbances": 0,
            "reason": "", "cause": "", "error": error}


def run_one(job: Job, method: str, rate: float, seed: int) -> Row:
    """Run `method` once; an error inside becomes the row's `error` column."""
    try:
        task, scenario, max_ticks = prepared(job)
        row = _measure(job, task, scenario, max_ticks, method, rate, seed)
    except BtplanError as error:
        return empty_row(job, method, rate, seed, f"{type(error).__name__}: {error}")
    except Exception as error:  # a bug in one run must not sink the sweep
        return empty_row(job, method, rate, seed, f"{type(error).__name__}: {error}")
    row.update(scenario=scenario.name, method=method, rate=rate, seed=seed, cause="",
               error="")
    return row


def _world(job: Job, task: Task, seed: int) -> tuple[Any, list[Any]]:
    if job.sim == "symbolic":
        from btplan.worlds.symbolic import SymbolicWorld

        return SymbolicWorld(task, seed=seed), []
    from btplan.worlds.pybullet import open_world

    world = open_world(task, seed=seed)
    return world, list(world.scene_agents())


def _measure(job: Job, task: Task, scenario: Scenario, max_ticks: int, method: str,
             rate: float, seed: int) -> Row:
    world, scene_agents = _world(job, task, seed)
    try:
        agents = [*scenario.agents_in(world, job.sim, task, rate, seed), *scene_agents]
        if method in BASELINES:
            out = run_baseline(task, world, agents, method, max_ticks)
            return {"success": out.reached, "ticks": out.ticks, "actions": out.actions,
                    "planner_calls": out.planner_calls,
                    "planning_seconds": out.planning_seconds,
                    "setup_seconds": out.setup_seconds,
                    "checks": out.checks / max(out.ticks, 1),
                    "disturbances": out.disturbances, "reason": out.reason}
        config = method_config(method, job.sim)
        started = time.process_time()
        models = acting.task_models(task, config.planner)
        setup = time.process_time() - started
        outcome = acting.run(task, agents=agents, world=world, seed=seed,
                             max_ticks=max_ticks, config=config, models=models)
    finally:
        if capabilities_of(world).closes:
            world.close()
    totals = outcome.summary()
    return {"success": outcome.reached, "ticks": outcome.ticks,
            "actions": len(outcome.executed),
            "planner_calls": totals.count("expansions"),
            "planning_seconds": totals.planning_seconds,
            "setup_seconds": setup,
            "checks": totals.checks / max(outcome.ticks, 1),
            "disturbances": totals.count("disturbances"),
            "reason": outcome.reason}


def method_config(method: str, sim: str) -> ActingConfig:
    """How btplan acts as `method`: `btplan-paper` is Algorithm 1 as published, `btplan`
    the preset `btplan run` uses in that world. Every method retries a failing action
    until the tick limit: the sweep gives each its whole budget."""
    if method == "btplan-paper":
        return ActingConfig.paper(retry_failed_actions=True)
    return ActingConfig.default() if sim == "symbolic" else ActingConfig.simulator()
