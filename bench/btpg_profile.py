"""Where a small planning call's time goes: btplan's load+plan on BTPG's single goals.

On BTPG's RoboWaiter goals most trees need one or two expansions, and btplan's time is
fixed costs, not search. This script splits the time of `load` and `plan` into phases
(reading, the relaxed model's reachability and grounding, h_add, h^2 mutexes, the loop,
the lower bound, plan improvement), then lists cProfile's top entries by cumulative
time, of load+plan and of plan() alone. Each after one untimed warm-up call, on the
first N distinct goals of the set.

The phase table comes from timers around the functions that start each phase (no
profiler: its overhead per Python call would inflate the phases that make many small
calls), each phase's own time, without the phases it calls; the garbage collector's
pauses are a phase of their own. A function it cannot find (btplan changed) is named
under the table and its time falls to the phase around it.

    python bench/btpg_profile.py                  # 5 goals, top 25
    python bench/btpg_profile.py --goals 10 --top 40
"""

from __future__ import annotations

import argparse
import cProfile
import gc
import importlib
import io
import json
import pstats
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
DEFAULT_SET = HERE / "problems" / "btpg_rw_single"

PHASES: list[tuple[str, str, str]] = [
    # (module, attribute path, phase); the outer call first, the phases inside it after
    ("btplan.acting.offline.planning", "load", "reading: the rest of load (task)"),
    ("btplan.lang.pddl_reader", "read_items", "reading: s-expressions"),
    ("btplan.lang.loader", "read_units", "reading: PDDL to syntax"),
    ("btplan.lang.loader", "build_domain", "reading: checking, building the domain"),
    ("btplan.lang.loader", "build_problem", "reading: checking, building the problem"),
    ("btplan.acting.offline.planning", "plan", "plan(): the rest (strategies, records)"),
    ("btplan.planner.achievers", "AchieverIndex.__init__",
     "set-up: achiever index (effects, objects, static bindings)"),
    ("btplan.acting.loop", "BlendedLoop.__init__", "set-up: the loop and its world"),
    ("btplan.acting.offline.planning", "attempt", "loop: ticks, expansions, tree growth"),
    ("btplan.planner.achievers", "AchieverIndex.achievers_avoiding",
     "loop: achiever look-up and ranking"),
    ("btplan.planner.achievers", "AchieverIndex.achievers", "loop: achiever look-up and ranking"),
    ("btplan.classical.heuristic", "_groundings", "relaxed model: reachability"),
    ("btplan.classical.heuristic", "RelaxedModel._ground",
     "relaxed model: grounding every action"),
    ("btplan.classical.heuristic", "RelaxedModel._encode", "relaxed model: encoding for h_add"),
    ("btplan.classical.heuristic", "RelaxedModel.costs", "heuristic: h_add costs"),
    ("btplan.classical.mutex", "Mutexes.__init__", "mutexes: h^2"),
    ("btplan.acting.offline.planning", "fewest_steps", "lower bound (LM-cut)"),
    ("btplan.acting.offline.improved", "improve_executed",
     "improvement: the rest (tree, replay)"),
    ("btplan.classical.packed", "PackedActions.__init__", "improvement: actions as bit masks"),
    ("btplan.acting.offline.improved", "improve", "improvement: neighbourhood search"),
]


GC_READING = "garbage collection while reading"
GC_PLANNING = "garbage collection while planning"


class PhaseClock:
    """Exclusive time per phase: the time between two calls or returns of the timed
    functions goes to the phase on top of the stack."""

    def __init__(self) -> None:
        self.spent: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        self.stack: list[str] = []
        self.mark = 0.0
        self.missing: list[str] = []

    def _switch(self) -> None:
        now = time.perf_counter()
        if self.stack:
            top = self.stack[-1]
            self.spent[top] = self.spent.get(top, 0.0) + now - self.mark
        self.mark = now

    def timed(self, phase: str, function: Callable[..., Any]) -> Callable[..., Any]:
        def run(*args: Any, **kwargs: Any) -> Any:
            self._switch()
            self.stack.append(phase)
            self.calls[phase] = self.calls.get(phase, 0) + 1
            try:
                return function(*args, **kwargs)
            finally:
                self._switch()
                self.stack.pop()
        return run

    def collecting(self, event: str, info: dict[str, int]) -> None:
        """A gc callback: the collector's pauses are a phase of their own (one while
        reading, one while planning), not the time of whichever phase they interrupt."""
        self._switch()
        if event == "start":
            reading = bool(self.stack) and self.stack[-1].startswith("reading")
            phase = GC_READING if reading else GC_PLANNING
            self.stack.append(phase)
            self.calls[phase] = self.calls.get(phase, 0) + 1
        elif self.stack and self.stack[-1] in (GC_READING, GC_PLANNING):
            self.stack.pop()

    @contextmanager
    def installed(self) -> Iterator[None]:
        """The timers in place of the functions of PHASES, for the block only."""
        gc.callbacks.append(self.collecting)
        undo: list[tuple[Any, str, Any]] = []
        for module_name, path, phase in PHASES:
            owner: Any = importlib.import_module(module_name)
            *outer, name = path.split(".")
            for part in outer:
                owner = getattr(owner, part, None)
            original = owner.__dict__.get(name) if owner is not None else None
            if original is None:
                self.missing.append(f"{module_name}.{path}")
                continue
            setattr(owner, name, self.timed(phase, original))
            undo.append((owner, name, original))
        try:
            yield
        finally:
            gc.callbacks.remove(self.collecting)
            for owner, name, original in reversed(undo):
                setattr(owner, name, original)


def problems(folder: Path, count: int) -> list[tuple[str, Path]]:
    """The first `count` distinct goals of the set: (goal, problem file)."""
    meta = json.loads((folder / "goals.json").read_text(encoding="utf-8"))
    seen: dict[str, Path] = {}
    for record in meta["records"]:
        if "problem" in record and record["goal"] not in seen:
            seen[record["goal"]] = folder / record["problem"]
    return list(seen.items())[:count]


def call(domain: Path, problem: Path, timeout: float) -> Any:
    """load+plan, through the modules' attributes (where the timers are)."""
    planning = importlib.import_module("btplan.acting.offline.planning")
    return planning.plan(planning.load(str(domain), str(problem)), timeout=timeout)


def phase_table(folder: Path, goals: list[tuple[str, Path]], timeout: float,
                rounds: int) -> list[str]:
    """The phases' own times over the goals, in the fastest of `rounds` rounds (the
    machine may be shared: the others had more of its time taken)."""
    domain = folder / "domain.pddl"
    call(domain, goals[0][1], timeout)  # warm-up
    kept: tuple[float, PhaseClock, list[Any]] | None = None
    for _ in range(rounds):
        clock = PhaseClock()
        with clock.installed():
            started = time.perf_counter()
            results = [call(domain, problem, timeout) for _, problem in goals]
            total = time.perf_counter() - started
        if kept is None or total < kept[0]:
            kept = (total, clock, results)
    assert kept is not None
    total, clock, results = kept
    per_goal = total / len(goals)
    expansions = [r.stats.expansions for r in results]
    lines = [f"{len(goals)} goals ({', '.join(g for g, _ in goals)}); expansions {expansions};"
             f" load+plan {1000 * per_goal:.2f} ms a goal (mean, timers in place, the fastest"
             f" of {rounds} rounds)", "",
             f"{'phase (its own time, without the phases it calls)':<60} {'ms/goal':>8} "
             f"{'share':>6} {'calls/goal':>10}"]
    for phase in sorted(clock.spent, key=clock.spent.__getitem__, reverse=True):
        seconds = clock.spent[phase] / len(goals)
        lines.append(f"{phase:<60} {1000 * seconds:>8.2f} {seconds / per_goal:>6.1%} "
                     f"{clock.calls[phase] / len(goals):>10.1f}")
    outside = per_goal - sum(clock.spent.values()) / len(goals)
    lines.append(f"{'(between the calls, in this script)':<60} {1000 * outside:>8.2f} "
                 f"{outside / per_goal:>6.1%}")
    if clock.missing:
        lines.append("not found in btplan (their time is in the phase around them): "
                     + ", ".join(clock.missing))
    return [*lines, "", *grouped(clock, len(goals))]


def grouped(clock: PhaseClock, goals: int) -> list[str]:
    """The phases by what they serve (the words before the colon), and the share of
    plan()'s time (reading left out) each takes."""
    groups: dict[str, float] = {}
    for phase, seconds in clock.spent.items():
        group = phase.split(":")[0]
        groups[group] = groups.get(group, 0.0) + seconds / goals
    apart = ("reading", GC_READING)
    planning = sum(v for k, v in groups.items() if k not in apart)
    lines = [f"{'by what it serves':<34} {'ms/goal':>8} {'of plan()':>10}"]
    for group in sorted(groups, key=groups.__getitem__, reverse=True):
        share = "" if group in apart else f"{groups[group] / planning:.1%}"
        lines.append(f"{group:<34} {1000 * groups[group]:>8.2f} {share:>10}")
    lines.append(f"{'plan() in all':<34} {1000 * planning:>8.2f} {'100.0%':>10}")
    return lines


def profile(folder: Path, goals: list[tuple[str, Path]], timeout: float, top: int,
            reading: bool) -> str:
    """cProfile's top entries by cumulative time over the goals: load+plan, or with
    `reading` False plan() alone (the tasks read beforehand)."""
    planning = importlib.import_module("btplan.acting.offline.planning")
    domain = folder / "domain.pddl"
    call(domain, goals[0][1], timeout)  # warm-up
    tasks = [] if reading else [planning.load(str(domain), str(p)) for _, p in goals]
    profiler = cProfile.Profile()
    profiler.enable()
    if reading:
        for _, problem in goals:
            call(domain, problem, timeout)
    else:
        for task in tasks:
            planning.plan(task, timeout=timeout)
    profiler.disable()
    text = io.StringIO()
    stats = pstats.Stats(profiler, stream=text)
    stats.strip_dirs().sort_stats("cumulative").print_stats(top)
    return text.getvalue().strip()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("goal_set", nargs="?", type=Path, default=DEFAULT_SET)
    parser.add_argument("--goals", type=int, default=5, help="the first N distinct goals")
    parser.add_argument("--top", type=int, default=25, help="cProfile entries to list")
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds of the phase timers; the fastest is shown")
    parser.add_argument("--timeout", type=float, default=10.0)
    args = parser.parse_args()
    folder = args.goal_set.resolve()
    goals = problems(folder, args.goals)
    print("\n".join(phase_table(folder, goals, args.timeout, args.rounds)))
    for reading, what in ((True, "load+plan"), (False, "plan() alone, the tasks read before")):
        print(f"\ncProfile of {what}, the same goals after a warm-up, top {args.top} by "
              "cumulative time:\n")
        print(profile(folder, goals, args.timeout, args.top, reading))


if __name__ == "__main__":
    main()
