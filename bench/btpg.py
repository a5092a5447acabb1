"""btplan beside BTPG's planners (OBTEA, HBTP, BTExpansion) on BTPG's own goal sets.

BTPG (the public benchmark `DIDS-EI/BTPG`, IJCAI 2024) synthesises a BT offline for a
goal in a grounded domain of robot actions. Its goal sets, converted to PDDL (one
parameterless action per grounded BTPG action, the same preconditions, effects and
costs; bench/problems/btpg_rw_single/ is the RoboWaiter single-goal set), are planned
here by both sides:

- btplan in this process, as BTPG is timed: the domain (BTPG's scene, its grounded
  actions) is read once, before any goal; for each goal, reading its problem against
  that domain (`btplan.lang.load_problem`) and `plan` (grounding, backchaining, acting
  in the symbolic world, plan improvement) are the time compared, after one untimed
  warm-up, the best of `--repeat` calls. The goals' tasks share the one domain, which
  keeps what planning builds for it, as a robot given one goal after another does.
  Reading the domain and problem anew for the goal (`load`) and planning is timed too,
  once, and so is the CLI's own summary line (`btplan plan`, one process a goal, whose
  time leaves out reading).
- BTPG's planners in BTPG's own Python, through bench/btpg_driver.py: the time of
  BTPG's `process()` (synthesis alone, with the scene's actions built beforehand), best
  of `--repeat` after a warm-up.

Every plan, btplan's and BTPG's (the actions BTPG's tree runs on BTPG's own model), is
replayed on the PDDL model by bench/validate_plan.py, which shares no code with btplan,
and counts as solved only when valid; its cost is the plan cost. Trees: a BTPG
condition leaf is a conjunction, a btplan condition one literal; both counts are in the
CSV. Expansions are each planner's own unit (BTPG: conditions expanded; btplan:
expansions of Algorithm 1).

BTPG's half needs BTPG's source and a Python environment with what its planning code
imports (its simulators and LLM clients are not needed; the driver stands in for them):

    git clone https://github.com/DIDS-EI/BTPG .btpg/src
    python -m venv .btpg/venv
    .btpg/venv/bin/pip install numpy sympy py_trees shortuuid antlr4-python3-runtime==4.13.1

    python bench/btpg.py --btpg-src .btpg/src --btpg-python .btpg/venv/bin/python
    python bench/btpg.py --first 2 --no-cli          # btplan alone, two goals

Without --btpg-src the BTPG half is skipped and btplan's numbers are printed alone.
A goal of a multi-goal set (bench/btpg_multi.py makes one from a single-goal set:
bench/problems/btpg_rw_multi/) is a conjunction, a set of literals to BTPG; when a
planner fails on some goals, the medians are also given over the goals all solve.
bench/results/btpg_rw_single.txt and btpg_rw_multi.txt are runs on the RoboWaiter sets.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.bt import Condition
from btplan.errors import BtplanError
from btplan.lang import load_domain, load_problem, with_goal
from btplan.model import Domain, Task

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
DEFAULT_SET = HERE / "problems" / "btpg_rw_single"
BTPLAN = "btplan"
BTPG_PLANNERS = ("OBTEA", "HBTP", "BTExpansion")
TARGET = ("BTPG {difficulty} goals: median planning time at most the best BTPG planner's, "
          "every goal solved, equal plan cost")

if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))
from validate_plan import validate  # noqa: E402  (bench/ is not a package)


@dataclass
class Goal:
    index: int
    name: str
    problem: Path
    atoms: tuple[str, ...] = ()
    """The goal's PDDL atoms, as goals.json lists them (the goal alone, `with_goal`)."""


@dataclass
class Outcome:
    """One planner on one goal. `seconds` is the time compared: btplan's problem reading
    and plan() on the domain read once, BTPG's process() on its scene built once."""

    planner: str
    index: int
    goal: str
    solved: bool = False
    seconds: float | None = None
    load_seconds: float | None = None
    goal_seconds: float | None = None
    """btplan: the goal alone on the scene read once (`with_goal`, then plan()), as BTPG's
    process() gets a goal on its scene built once; None where the problem's objects or
    initial state differ from the scene's."""
    plan_seconds: float | None = None
    fresh_seconds: float | None = None
    """btplan: reading domain and problem anew, then planning (no model kept)."""
    cli_seconds: float | None = None
    cli_wall_seconds: float | None = None
    expansions: int | None = None
    tree_nodes: int | None = None
    condition_nodes: int | None = None
    condition_literals: int | None = None
    plan_length: int | None = None
    plan_cost: float | None = None
    note: str = ""


@dataclass
class GoalSet:
    name: str
    folder: Path
    domain: Path
    goals: list[Goal]
    btpg_names: dict[str, str]
    """BTPG's action names to the PDDL ones."""
    difficulty: str = "single"
    """"single" (one goal literal) or "multi" (a conjunction, bench/btpg_multi.py)."""


def read_set(folder: Path, first: int | None) -> GoalSet:
    meta = json.loads((folder / "goals.json").read_text(encoding="utf-8"))
    goals = [Goal(r["index"], r["goal"], folder / r["problem"], tuple(r.get("atoms", ())))
             for r in meta["records"] if "problem" in r][:first]
    names = {btpg: pddl for pddl, btpg in meta["action_names"].items()}
    return GoalSet(folder.name, folder, folder / "domain.pddl", goals, names,
                   meta.get("difficulty", "single"))


def checked(outcome: Outcome, goals: GoalSet, goal: Goal, steps: Sequence[str]) -> Outcome:
    """The outcome, solved only when its plan (IPC steps) is valid on the PDDL model."""
    ok, reason, cost = validate(goals.domain.read_text(encoding="utf-8"),
                                goal.problem.read_text(encoding="utf-8"), "\n".join(steps))
    outcome.plan_length = len(steps)
    outcome.plan_cost = cost if ok else None
    if not ok:
        outcome.solved = False
        outcome.note = f"invalid plan: {reason}"
    return outcome


# --- btplan -------------------------------------------------------------------------------


def btplan_goal(goals: GoalSet, goal: Goal, timeout: float, repeat: int,
                domain: Domain, scene: Task | None = None) -> Outcome:
    """btplan on one goal in this process: the best of `repeat` problem+plan calls on the
    domain read once, the best of `repeat` calls giving the goal alone on `scene` (the
    first problem, read once) where the problem's scene is the same, and one call that
    reads both files anew."""
    out = Outcome(BTPLAN, goal.index, goal.name)
    best = (float("inf"), 0.0, 0.0)
    try:
        for _ in range(repeat):
            started = time.perf_counter()
            task = load_problem(domain, str(goal.problem))
            loaded = time.perf_counter()
            result = plan(task, timeout=timeout)
            done = time.perf_counter()
            best = min(best, (done - started, loaded - started, done - loaded))
        if scene is not None and goal.atoms and same_scene(task, scene):
            out.goal_seconds = goal_alone(scene, goal, timeout, repeat)
        started = time.perf_counter()
        plan(load(str(goals.domain), str(goal.problem)), timeout=timeout)
        out.fresh_seconds = time.perf_counter() - started
    except BtplanError as error:
        out.note = str(error)[:160]
        return out
    out.seconds, out.load_seconds, out.plan_seconds = best
    stats = result.stats
    out.expansions, out.tree_nodes = stats.expansions, stats.tree_size
    out.condition_nodes = sum(isinstance(n, Condition) for n in result.tree.nodes())
    out.condition_literals = out.condition_nodes  # one literal per condition
    out.solved = True
    return checked(out, goals, goal, [a.ipc() for a in result.executed])


def same_scene(task: Task, scene: Task) -> bool:
    """Whether `task` differs from `scene` in its goal alone."""
    return (task.problem.objects == scene.problem.objects
            and task.problem.init == scene.problem.init
            and task.problem.values == scene.problem.values)


def goal_alone(scene: Task, goal: Goal, timeout: float, repeat: int) -> float:
    """The best of `repeat` calls reading the goal alone against `scene` and planning it."""
    text = f"(and {' '.join(goal.atoms)})"
    best = float("inf")
    for _ in range(repeat):
        started = time.perf_counter()
        plan(with_goal(scene, text), timeout=timeout)
        best = min(best, time.perf_counter() - started)
    return best


SUMMARY = re.compile(r"planned: .*? executed \(cost [^)]*\), ([0-9.]+) s")


def cli_goal(goals: GoalSet, goal: Goal, timeout: float, out: Outcome) -> None:
    """The time on `btplan plan`'s own summary line (reading left out), and its wall time."""
    env = dict(os.environ, COLUMNS="1000",
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    with tempfile.TemporaryDirectory() as folder:
        started = time.perf_counter()
        run = subprocess.run(
            [sys.executable, "-m", "btplan", "plan", str(goals.domain), str(goal.problem),
             "-o", os.path.join(folder, "tree.json"), "--timeout", f"{timeout:g}"],
            capture_output=True, text=True, env=env, cwd=folder)
        out.cli_wall_seconds = time.perf_counter() - started
    found = SUMMARY.search(" ".join(run.stderr.split()))
    if run.returncode == 0 and found:
        out.cli_seconds = float(found.group(1))


def btplan_half(goals: GoalSet, timeout: float, repeat: int, cli: bool) -> list[Outcome]:
    """btplan on every goal; the domain is read once, untimed, as BTPG builds its scene."""
    domain = load_domain(str(goals.domain))
    scene = load_problem(domain, str(goals.goals[0].problem)) if goals.goals else None
    if goals.goals:  # warm-up: imports and first-call caches are not the planner's time
        fresh = load_domain(str(goals.domain))
        btplan_goal(goals, goals.goals[0], timeout, 1, fresh,
                    load_problem(fresh, str(goals.goals[0].problem)))
    outcomes = []
    for goal in goals.goals:
        out = btplan_goal(goals, goal, timeout, repeat, domain, scene)
        if cli:
            cli_goal(goals, goal, timeout, out)
        progress(out)
        outcomes.append(out)
    return outcomes


# --- BTPG ---------------------------------------------------------------------------------


def btpg_lines(python: str, source: Path, goals: GoalSet, timeout: float, repeat: int,
               first: int | None, just_best: bool) -> Iterator[dict[str, object]]:
    """The driver's JSON lines, as it prints them."""
    command = [python, str(HERE / "btpg_driver.py"), str(source), str(goals.folder / "goals.json"),
               "--timeout", f"{timeout:g}", "--repeat", str(repeat)]
    if first is not None:
        command += ["--first", str(first)]
    if just_best:
        command.append("--just-best")
    # BTPG's results depend on the iteration order of Python's sets of strings.
    env = dict(os.environ, PYTHONHASHSEED="0")
    with subprocess.Popen(command, stdout=subprocess.PIPE, text=True, env=env) as driver:
        assert driver.stdout is not None
        for line in driver.stdout:
            if line.startswith("{"):
                yield json.loads(line)
    if driver.returncode:
        raise SystemExit(f"the BTPG driver failed (exit {driver.returncode})")


def btpg_half(python: str, source: Path, goals: GoalSet, timeout: float, repeat: int,
              first: int | None, just_best: bool) -> list[Outcome]:
    by_index = {g.index: g for g in goals.goals}
    outcomes = []
    for row in btpg_lines(python, source, goals, timeout, repeat, first, just_best):
        goal = by_index[int(row["index"])]  # type: ignore[call-overload]
        out = Outcome(str(row["planner"]), goal.index, goal.name, bool(row["solved"]),
                      note=str(row.get("note", "")))
        for key in ("seconds", "expansions", "tree_nodes", "condition_nodes",
                    "condition_literals"):
            setattr(out, key, row.get(key))
        if out.solved:
            names = [str(n) for n in row["plan"]]  # type: ignore[attr-defined]
            unknown = [n for n in names if n not in goals.btpg_names]
            steps = [f"({goals.btpg_names.get(n, n)})" for n in names]
            checked(out, goals, goal, steps)
            if unknown:
                out.solved, out.note = False, f"actions outside the domain: {unknown[:3]}"
        progress(out)
        outcomes.append(out)
    return outcomes


TIMES = ("seconds", "load_seconds", "goal_seconds", "plan_seconds", "fresh_seconds",
         "cli_seconds", "cli_wall_seconds")
"""The times of an outcome; every other field is the same in every round."""


def fastest(rounds: Sequence[Sequence[Outcome]]) -> list[Outcome]:
    """The first round's outcomes, each time the least the rounds measured for that
    planner and goal: the halves ran in turn, so a spell of a slower machine falls on
    both sides."""
    first = rounds[0]
    for out in first:
        same = [o for r in rounds for o in r if (o.planner, o.index) == (out.planner, out.index)]
        for name in TIMES:
            values = [getattr(o, name) for o in same if getattr(o, name) is not None]
            setattr(out, name, min(values) if values else None)
    return list(first)


def progress(out: Outcome) -> None:
    seconds = "-" if out.seconds is None else f"{1000 * out.seconds:.2f} ms"
    print(f"[{out.index:3}] {out.goal:<28} {out.planner:<12} "
          f"{'ok' if out.solved else 'FAILED'} {seconds} {out.note}", file=sys.stderr, flush=True)


# --- the report ---------------------------------------------------------------------------


def median(values: Sequence[float | int | None]) -> float | None:
    present = [float(v) for v in values if v is not None]
    return statistics.median(present) if present else None


def number(value: float | None, digits: int = 1) -> str:
    if value is None:
        return "-"
    return f"{value:.0f}" if float(value).is_integer() else f"{value:.{digits}f}"


def ms(value: float | None) -> str:
    return "-" if value is None else f"{1000 * value:.2f}"


def planner_table(outcomes: Sequence[Outcome], planners: Sequence[str]) -> list[str]:
    """Per planner, over the goals it solved: solved count and medians."""
    lines = [f"{'planner':<12} {'solved':>8} {'median ms':>10} {'tree nodes':>11} "
             f"{'expansions':>11} {'plan cost':>10}"]
    for planner in planners:
        mine = [o for o in outcomes if o.planner == planner]
        ok = [o for o in mine if o.solved]
        lines.append(
            f"{planner:<12} {len(ok):>4}/{len(mine):<3} {ms(median([o.seconds for o in ok])):>10} "
            f"{number(median([o.tree_nodes for o in ok])):>11} "
            f"{number(median([o.expansions for o in ok])):>11} "
            f"{number(median([o.plan_cost for o in ok])):>10}")
    return lines


def best_of(others: Sequence[Outcome], key: str) -> Outcome | None:
    """The solved BTPG outcome with the smallest `key` (planners in table order on ties)."""
    present = [o for o in others if o.solved and getattr(o, key) is not None]
    return min(present, key=lambda o: getattr(o, key)) if present else None


def ratio(mine: float | None, theirs: float | None) -> float | None:
    return None if mine is None or not theirs else mine / theirs


def per_goal(outcomes: Sequence[Outcome]) -> tuple[list[str], dict[str, list[float]]]:
    """One line a goal: btplan over the best BTPG planner of that goal, measure by measure."""
    lines = [f"{'goal':>4} {'name':<28} {'fastest BTPG':<12} {'its ms':>7} {'btplan ms':>9} "
             f"{'time':>7} {'nodes':>6} {'exp.':>6}  cost btplan/best"]
    ratios: dict[str, list[float]] = {"time": [], "nodes": [], "expansions": []}
    keys = {"time": "seconds", "nodes": "tree_nodes", "expansions": "expansions"}
    for index in sorted({o.index for o in outcomes}):
        here = [o for o in outcomes if o.index == index]
        mine = next((o for o in here if o.planner == BTPLAN), None)
        others = [o for o in here if o.planner != BTPLAN]
        if mine is None or not mine.solved or not others:
            continue
        values: dict[str, float | None] = {}
        for name, key in keys.items():
            best = best_of(others, key)
            values[name] = ratio(getattr(mine, key), None if best is None else getattr(best, key))
            if values[name] is not None:
                ratios[name].append(values[name])  # type: ignore[arg-type]
        fastest, cheapest = best_of(others, "seconds"), best_of(others, "plan_cost")
        lines.append(
            f"{index:>4} {mine.goal[:28]:<28} {fastest.planner if fastest else '-':<12} "
            f"{ms(fastest.seconds if fastest else None):>7} {ms(mine.seconds):>9} "
            f"{times(values['time'], 1):>7} {times(values['nodes']):>6} "
            f"{times(values['expansions']):>6}  "
            f"{number(mine.plan_cost)}/{number(cheapest.plan_cost if cheapest else None)}")
    return lines, ratios


def times(value: float | None, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}f}x"


def verdict(ok: bool) -> str:
    return "met" if ok else "missed"


def lowest_cost(outcomes: Sequence[Outcome], index: int) -> float | None:
    """The lowest plan cost a BTPG planner found for goal `index` (OBTEA's and HBTP's are
    optimal)."""
    costs = [o.plan_cost for o in outcomes if o.index == index and o.planner != BTPLAN
             and o.solved and o.plan_cost is not None]
    return min(costs) if costs else None


def common_goals(outcomes: Sequence[Outcome], planners: Sequence[str]) -> list[str]:
    """Medians over the goals every planner solved, so that no planner's median leaves out
    the goals it failed on; btplan's against the BTPG planner fastest there."""
    indices = {o.index for o in outcomes}
    common = sorted(i for i in indices if all(
        any(o.index == i and o.planner == p and o.solved for o in outcomes) for p in planners))
    if len(planners) < 2 or len(common) == len(indices) or not common:
        return []
    shared = [o for o in outcomes if o.index in common]
    lines = ["", f"on the {len(common)} goals all {len(planners)} planners solve:",
             *planner_table(shared, planners)]
    medians = {p: median([o.seconds for o in shared if o.planner == p]) for p in planners}
    theirs = [p for p in planners if p != BTPLAN]
    if BTPLAN in planners and theirs:
        best = min(theirs, key=lambda p: medians[p] or float("inf"))
        lines.append(f"btplan {ms(medians[BTPLAN])} ms vs {best} {ms(medians[best])} ms: "
                     f"{times(ratio(medians[BTPLAN], medians[best]))}")
    return lines


def targets(outcomes: Sequence[Outcome], difficulty: str) -> list[str]:
    """The target, judged against the BTPG planner with the lowest median time."""
    target = TARGET.format(difficulty=difficulty)
    mine = [o for o in outcomes if o.planner == BTPLAN]
    theirs = [p for p in BTPG_PLANNERS if any(o.planner == p and o.solved for o in outcomes)]
    if not theirs:
        return [f"target  {target}: not judged (no BTPG run: give --btpg-src and --btpg-python)"]
    medians = {p: median([o.seconds for o in outcomes if o.planner == p and o.solved])
               for p in theirs}
    best = min(theirs, key=lambda p: medians[p] or float("inf"))
    solved = [o for o in mine if o.solved]
    mine_total = median([o.seconds for o in solved])
    mine_plan = median([o.plan_seconds for o in solved])
    mine_fresh = median([o.fresh_seconds for o in solved])
    mine_goal = median([o.goal_seconds for o in solved])
    fast = mine_total is not None and mine_total <= (medians[best] or 0.0)
    equal = sum(o.plan_cost is not None and o.plan_cost == lowest_cost(outcomes, o.index)
                for o in solved)
    all_solved = len(solved) == len(mine) > 0
    return [
        f"target  {target}: {verdict(fast and all_solved and equal == len(mine))}",
        f"  median planning time: btplan {ms(mine_total)} ms (problem+plan) vs {best} "
        f"{ms(medians[best])} ms (process()), {times(ratio(mine_total, medians[best]), 1)}: "
        f"{verdict(fast)}",
        f"    (btplan's plan() alone, reading the problem left out: {ms(mine_plan)} ms, "
        f"{times(ratio(mine_plan, medians[best]), 1)}; domain and problem read anew and "
        f"planned: {ms(mine_fresh)} ms, {times(ratio(mine_fresh, medians[best]), 0)})",
        *([] if mine_goal is None else [
            f"  the goal alone on the scene read once (with_goal and plan(), as process() gets "
            f"its goal on its scene): btplan {ms(mine_goal)} ms vs {best} {ms(medians[best])} "
            f"ms, {times(ratio(mine_goal, medians[best]), 1)}: "
            f"{verdict(mine_goal <= (medians[best] or 0.0))}"]),
        f"  every goal solved: {len(solved)}/{len(mine)}: {verdict(all_solved)}",
        f"  plan cost equal to the best BTPG planner's: {equal}/{len(mine)} goals: "
        f"{verdict(equal == len(mine))}",
    ]


def report(goals: GoalSet, outcomes: Sequence[Outcome], timeout: float, repeat: int,
           rounds: int = 1) -> str:
    planners = [p for p in (*BTPG_PLANNERS, BTPLAN) if any(o.planner == p for o in outcomes)]
    distinct = len({g.name for g in goals.goals})
    turns = f", in {rounds} rounds of both sides in turn," if rounds > 1 else ""
    lines = [f"{goals.name}: {len(goals.goals)} goals ({distinct} distinct), limit {timeout:g} s;"
             f" time: best of {repeat} in-process calls{turns} after a warm-up (btplan: the problem"
             " read against the domain read once, and plan(); BTPG: process() on its scene"
             " built once); medians over the goals each planner solved", ""]
    lines += planner_table(outcomes, planners)
    mine = [o for o in outcomes if o.planner == BTPLAN and o.solved]
    if mine:
        lines += ["", f"btplan's time apart: reading the problem "
                  f"{ms(median([o.load_seconds for o in mine]))} ms, plan() "
                  f"{ms(median([o.plan_seconds for o in mine]))} ms; domain and problem read "
                  f"anew, then plan(): {ms(median([o.fresh_seconds for o in mine]))} ms; "
                  f"the goal alone on the scene read once, then plan(): "
                  f"{ms(median([o.goal_seconds for o in mine]))} ms (medians)"]
        if any(o.cli_seconds is not None for o in mine):
            lines.append(f"btplan plan (CLI): summary-line time "
                         f"{ms(median([o.cli_seconds for o in mine]))} ms, whole process "
                         f"{ms(median([o.cli_wall_seconds for o in mine]))} ms (medians)")
    failed = [o for o in outcomes if not o.solved]
    for o in failed:
        lines.append(f"not solved: {o.planner} on goal {o.index} ({o.goal}): {o.note}")
    goal_lines, ratios = per_goal(outcomes)
    if len(goal_lines) > 1:
        lines += ["", "btplan / best BTPG planner of each goal (time: the fastest; nodes, "
                  "expansions: the fewest; cost: btplan's / the lowest):", *goal_lines]
        lines.append("median of the ratios: " + ", ".join(
            f"{key} {times(median(values))}" for key, values in ratios.items()))
    lines += common_goals(outcomes, planners)
    lines += ["", *targets(outcomes, goals.difficulty)]
    return "\n".join(lines)


def write_csv(path: str, outcomes: Sequence[Outcome], name: str) -> None:
    columns = ["set", *(f.name for f in fields(Outcome))]
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, columns)
        writer.writeheader()
        for o in outcomes:
            writer.writerow({"set": name, **asdict(o)})


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("goal_set", nargs="?", type=Path, default=DEFAULT_SET,
                        help="a folder of PDDL problems with goals.json "
                             "(default: bench/problems/btpg_rw_single)")
    parser.add_argument("--btpg-src", type=Path, help="BTPG's exported source folder")
    parser.add_argument("--btpg-python", default=sys.executable,
                        help="the Python of BTPG's virtual environment")
    parser.add_argument("--timeout", type=float, default=10.0)
    parser.add_argument("--repeat", type=int, default=3, help="timed calls a goal; the best counts")
    parser.add_argument("--rounds", type=int, default=3,
                        help="rounds of both halves, in turn; each time is the least over "
                             "the rounds (a shared machine's speed changes within minutes)")
    parser.add_argument("--first", type=int, help="only the first N goals")
    parser.add_argument("--no-cli", action="store_true",
                        help="skip the `btplan plan` process run for each goal")
    parser.add_argument("--btpg-just-best", action="store_true",
                        help="BTPG keeps only the cheapest branch in its tree "
                             "(output_just_best; its RoboWaiter example keeps them all)")
    parser.add_argument("--out", help="write one CSV row per goal and planner here")
    args = parser.parse_args(argv)
    goals = read_set(args.goal_set.resolve(), args.first)
    rounds: list[list[Outcome]] = []
    for number in range(args.rounds):
        halves: list[Callable[[], list[Outcome]]] = [
            lambda: btplan_half(goals, args.timeout, args.repeat, not args.no_cli and not number)]
        if args.btpg_src is not None:
            halves.append(lambda: btpg_half(args.btpg_python, args.btpg_src.resolve(), goals,
                                            args.timeout, args.repeat, args.first,
                                            args.btpg_just_best))
        if number % 2 == 0:
            halves.reverse()  # BTPG first, then btplan; the other way round next time
        rounds.append([out for half in halves for out in half()])
    outcomes = fastest(rounds)
    print(report(goals, outcomes, args.timeout, args.repeat, args.rounds))
    if args.out:
        write_csv(args.out, outcomes, goals.name)


if __name__ == "__main__":
    main()
