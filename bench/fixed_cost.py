"""What one planning call costs on small problems, phase by phase, in one process.

On a small grounded domain the search itself takes a few milliseconds, and what a call
costs beyond it is the work done before and after: grounding, reachability, mutexes,
the lower bound, the improvement pass. This bench plans BTPG's RoboWaiter single goals
(bench/problems/btpg_rw_single: 174 parameterless actions, 42 goals) and Example 2
(domains/pick_place_obstacle.bt, planned, and run with examples/example2.dist, whose
run plans before acting). Each case is timed --repeat times, keeping each problem's
fastest call (the machine may be shared), in two ways: `new`, every call on a task
loaded anew (so its domain is another object, and nothing an earlier call kept is
found: a `btplan plan` process's one call, its imports aside), and `again`, the same
task planned again (as an acting run replans, or a caller plans many goals of one
domain). Each call's time is split into phases by wrapping the planner's functions with
timers: a phase's time is exclusive (a phase entered inside another is taken out of
the outer one), and `other` is the rest of the call. For RW the table gives, for each
phase, the median over the goals (so the phases need not add up to the median call).

The very first call of the process is timed on its own too (`first call`): it
imports what planning loads on first use, as the one call of a `btplan plan` process
does (its summary line counts from the same place). --cold plans every goal that way,
one process each, and gives the median.

With --save, the phases and each call's plan and tree size go to a JSON file; with
--before, a saved run is shown beside this one, and the calls whose plan or tree size
differ are named. Run against an older source tree (PYTHONPATH), the bench times that
tree's planner: the functions it wraps that the older tree lacks are marked optional.

    python bench/fixed_cost.py                                   # the tables
    python bench/fixed_cost.py --save before.json --cold
    python bench/fixed_cost.py --before before.json --cold       # before | now
"""

from __future__ import annotations

import argparse
import functools
import gc
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
RW = ROOT / "bench" / "problems" / "btpg_rw_single"
EXAMPLE2 = ROOT / "domains" / "pick_place_obstacle.bt"
SCENARIO = ROOT / "examples" / "example2.dist"

from btplan.acting.offline import load, plan  # noqa: E402  (before anything else: --first)

COLD = """
import sys, time
from btplan.acting.offline import load, plan
task = load(sys.argv[1], sys.argv[2])
start = time.perf_counter()
plan(task)
print(time.perf_counter() - start)
"""
"""One planning call in a fresh process, timed as `btplan plan`'s summary line is."""

PHASES: list[tuple[str, str, str, str]] = [
    # (phase, module, owner in the module ("" for the module itself), function)
    ("reachability", "btplan.classical.heuristic", "", "reachable_bindings"),
    ("grounding", "btplan.classical.heuristic", "RelaxedModel", "__init__"),
    ("achiever index", "btplan.planner.achievers", "AchieverIndex", "__init__"),
    ("h_add", "btplan.classical.heuristic", "RelaxedModel", "costs"),
    ("h_add", "btplan.classical.heuristic", "RelaxedModel", "reachable_avoiding"),
    ("h^2 mutexes", "btplan.classical.mutex", "Mutexes", "__init__"),
    ("h^2 mutexes", "btplan.classical.mutex", "Mutexes", "_build?"),
    ("invariants", "btplan.classical.invariants", "MutexGroups", "__init__"),
    ("lower bound", "btplan.acting.offline.planning", "", "fewest_steps"),
    ("lower bound", "btplan.acting.offline.planning", "", "no_better_plan?"),
    ("packing", "btplan.classical.packed", "PackedActions", "__init__"),
    ("improvement", "btplan.acting.offline.improved", "", "improve_executed"),
    ("search", "btplan.classical.search", "SearchRun", "resume"),
    ("loop setup", "btplan.acting.loop", "BlendedLoop", "__init__"),
    ("expansion", "btplan.acting.loop", "BlendedLoop", "expand"),
    ("ticks", "btplan.acting.loop", "BlendedLoop", "tick"),
]
"""Where each phase is timed. Lower rows run inside upper ones (a tick expands, an
expansion builds the relaxed model on first use), and the times are exclusive. A name
ending in `?` may be missing (an older version, compared with --before, lacks it)."""

ORDER = [*dict.fromkeys(p for p, *_ in PHASES), "other", "call"]


class Timers:
    """Exclusive seconds per phase, over the wrapped functions."""

    def __init__(self) -> None:
        self.spent: dict[str, float] = {}
        self._open: list[list[float]] = []  # [started, seconds of inner phases]

    def wrap(self, phase: str, module: str, owner: str, name: str) -> None:
        import importlib

        home: Any = importlib.import_module(module)
        if owner:
            home = getattr(home, owner)
        if name.endswith("?"):
            name = name[:-1]
            if name not in (home.__dict__ if owner else vars(home)):
                return
        original = home.__dict__[name] if owner else getattr(home, name)
        opened, spent = self._open, self.spent

        @functools.wraps(original)
        def timed(*args: Any, **kwargs: Any) -> Any:
            frame = [time.perf_counter(), 0.0]
            opened.append(frame)
            try:
                return original(*args, **kwargs)
            finally:
                opened.pop()
                took = time.perf_counter() - frame[0]
                spent[phase] = spent.get(phase, 0.0) + took - frame[1]
                if opened:
                    opened[-1][1] += took

        setattr(home, name, timed)

    def measure(self, call: Callable[[], Any]) -> tuple[dict[str, float], Any]:
        """Milliseconds per phase of one call (with `other` and the whole `call`), and
        what it returned."""
        self.spent.clear()
        start = time.perf_counter()
        out = call()
        total = time.perf_counter() - start
        ms = {phase: 1000 * s for phase, s in self.spent.items()}
        ms["other"] = 1000 * total - sum(ms.values())
        ms["call"] = 1000 * total
        return ms, out


def fastest(timers: Timers, prepare: Callable[[], Callable[[], Any]], repeat: int
            ) -> tuple[dict[str, float], Any]:
    """The phases of the fastest of `repeat` calls, each made by `prepare` (untimed, and
    its garbage collected before the call: reading a domain leaves a collection due)."""
    best: tuple[dict[str, float], Any] | None = None
    for _ in range(repeat):
        call = prepare()
        gc.collect()
        ms, out = timers.measure(call)
        if best is None or ms["call"] < best[0]["call"]:
            best = (ms, out)
    assert best is not None
    return best


def planned(result: Any) -> dict[str, Any]:
    """What must stay the same from one version to the next: the plan and the tree size."""
    return {"plan": [str(a) for a in result.executed], "cost": result.stats.cost,
            "tree": result.stats.tree_size}


def acted(outcome: Any) -> dict[str, Any]:
    return {"plan": [str(a) for a in outcome.executed], "reached": outcome.reached,
            "tree": len(outcome.tree.nodes())}


def medians(rows: list[dict[str, float]]) -> dict[str, float]:
    return {phase: statistics.median(r.get(phase, 0.0) for r in rows) for phase in ORDER}


def cold_times(problems: list[Path]) -> list[float]:
    """Milliseconds of one planning call per problem, each in a fresh process of the
    btplan this process imported (from another folder: `python -c` puts the working
    folder first on sys.path)."""
    import btplan

    env = {**os.environ, "PYTHONPATH": str(Path(btplan.__file__).resolve().parents[1])}
    out = []
    with tempfile.TemporaryDirectory() as elsewhere:
        for problem in problems:
            done = subprocess.run([sys.executable, "-c", COLD, str(RW / "domain.pddl"),
                                   str(problem)], check=True, capture_output=True, text=True,
                                  cwd=elsewhere, env=env)
            out.append(1000 * float(done.stdout.split()[-1]))
    return out


def table(columns: dict[str, dict[str, float]]) -> str:
    width = max(12, *(len(c) + 1 for c in columns))
    lines = [f"{'phase (ms)':<16}" + "".join(f"{c:>{width}}" for c in columns)]
    for phase in [*ORDER, "first call", "cold median"]:
        if not any(phase in col for col in columns.values()):
            continue
        cells = "".join(f"{col[phase]:>{width}.2f}" if phase in col else f"{'':>{width}}"
                        for col in columns.values())
        lines.append(f"{phase:<16}" + cells)
    return "\n".join(lines)


CASES = {
    "rw new": "RW single goals, a task loaded anew for each call (nothing kept from earlier calls)",
    "rw again": "RW single goals, the same task planned again (what earlier calls kept is used)",
    "ex2 plan new": "Example 2 planned, a task loaded anew for each call",
    "ex2 plan again": "Example 2 planned again",
    "ex2 run new": "Example 2 run with its scenario (it plans before acting), a task loaded anew",
    "ex2 run again": "Example 2 run again",
}


def call_on(act: Callable[[Any], Any], task: Any) -> Callable[[], Any]:
    return lambda: act(task)


def measured(timers: Timers, repeat: int) -> tuple[dict[str, dict[str, float]],
                                                   dict[str, Any]]:
    """Each case's phases (medians over the goals for RW), and what each call made."""
    from btplan.acting.online import run
    from btplan.worlds.disturb import parse_scenario

    runs: dict[str, Any] = {}
    new: list[dict[str, float]] = []
    again: list[dict[str, float]] = []
    for problem in sorted(RW.glob("p*.pddl")):
        paths = (str(RW / "domain.pddl"), str(problem))
        ms, result = fastest(timers, lambda: call_on(plan, load(*paths)), repeat)
        new.append(ms)
        runs[f"rw/{problem.stem}"] = planned(result)
        task = load(*paths)
        plan(task)
        ms, result = fastest(timers, lambda: call_on(plan, task), repeat)
        again.append(ms)
        runs[f"rw/{problem.stem} again"] = planned(result)
    cases = {"rw new": medians(new), "rw again": medians(again)}
    specs = parse_scenario(SCENARIO.read_text(), str(SCENARIO))
    acts: list[tuple[str, Callable[[Any], Any], Callable[[Any], dict[str, Any]]]] = [
        ("plan", plan, planned), ("run", lambda task: run(task, disturb=specs), acted)]
    for kind, act, keep in acts:
        ms, out = fastest(timers, lambda: call_on(act, load(str(EXAMPLE2))), repeat)
        cases[f"ex2 {kind} new"] = ms
        runs[f"example2/{kind}"] = keep(out)
        example = load(str(EXAMPLE2))
        act(example)
        ms, out = fastest(timers, lambda: call_on(act, example), repeat)
        cases[f"ex2 {kind} again"] = ms
        runs[f"example2/{kind} again"] = keep(out)
    return cases, runs


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="calls timed per problem")
    parser.add_argument("--cold", action="store_true",
                        help="also one fresh process per goal (the CLI's case)")
    parser.add_argument("--save", help="write this run to a JSON file")
    parser.add_argument("--before", help="a saved run to show beside this one")
    parser.add_argument("--label", default="now", help="this run's name in the table")
    args = parser.parse_args()
    first = load(str(RW / "domain.pddl"), str(RW / "p000.pddl"))
    start = time.perf_counter()
    plan(first)  # nothing planning loads on first use is loaded yet
    first_ms = 1000 * (time.perf_counter() - start)
    timers = Timers()
    for phase, module, owner, name in PHASES:
        timers.wrap(phase, module, owner, name)
    cases, runs = measured(timers, args.repeat)
    cases["rw new"]["first call"] = first_ms
    if args.cold:
        cases["rw new"]["cold median"] = statistics.median(
            cold_times(sorted(RW.glob("p*.pddl"))))
    now = {"date": time.strftime("%Y-%m-%d"), "label": args.label, "cases": cases,
           "runs": runs}
    before = json.loads(Path(args.before).read_text()) if args.before else None
    print(f"{now['date']}: each problem's fastest of {args.repeat} calls; for RW the median "
          "over the 42 goals of each phase (so the phases need not add up to the call)")
    for case, title in CASES.items():
        print(f"\n{title}")
        columns = {now["label"]: cases[case]}
        if before is not None:
            columns = {before["label"]: before["cases"][case], **columns}
        print(table(columns))
    again = [k for k in runs if k.endswith(" again") and runs[k] != runs[k[:-len(" again")]]]
    print(f"\nplanned again as the first time: {len(runs) // 2 - len(again)} of {len(runs) // 2}"
          + (f"; differ: {', '.join(again)}" if again else ""))
    if before is not None:
        changed = [key for key, seen in runs.items() if before["runs"].get(key) != seen]
        print(f"plans and tree sizes as before: {len(runs) - len(changed)} of {len(runs)}"
              + (f"; differ: {', '.join(changed)}" if changed else ""))
    if args.save:
        Path(args.save).write_text(json.dumps(now, indent=1) + "\n")


if __name__ == "__main__":
    main()
