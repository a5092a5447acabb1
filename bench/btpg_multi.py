"""A multi-goal set made from a single-goal set: each problem asks for K single goals at once.

BTPG's planners and btplan are compared on goal sets in the form of
bench/problems/btpg_rw_single/ (`domain.pddl`, one `pNNN.pddl` a goal, `goals.json`).
BTPG's own multi-goal sets are kept aside to check against, so the multi-goal set
trained on is made here from the single goals: a problem is the conjunction of K
distinct single goals (their atoms differ), drawn at random with `--seed`, from the
same initial state, `--count` problems for each K of `--sizes`. No conjunction is
drawn twice.

Two goals may not hold together (the robot near two tables, holding two things), so a
conjunction is kept only when it is shown solvable: pyperplan's greedy best-first
search with the FF heuristic finds a plan, within `--max-states` evaluated states and
`--time-limit` seconds, on the domain with its action costs left out (pyperplan reads
no costs; they do not change what is reachable), and bench/validate_plan.py accepts
that plan on the domain as it is. The check is pyperplan's, not btplan's, so the set
keeps no goal because btplan solves it and drops none because it fails it: a
conjunction btplan cannot solve stays in and counts against it. Rejected draws are
counted by reason and written to `goals.json`; those that hit a limit are not proved
unsolvable, only left out (the state cap, not the clock, decides first, so the same
command gives the same set on any machine).

    python bench/btpg_multi.py bench/problems/btpg_rw_single bench/problems/btpg_rw_multi
    python bench/btpg_multi.py SINGLE OUT --sizes 2,3 --count 20 --seed 0
"""

from __future__ import annotations

import argparse
import json
import random
import re
import shutil
import sys
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))
from validate_plan import validate  # noqa: E402  (bench/ is not a package)

MAX_DRAWS = 50
"""Draws allowed for each problem wanted before a size is given up as too hard to fill."""


@dataclass(frozen=True)
class Single:
    """One distinct goal of the single-goal set (the first record with its atoms)."""

    index: int
    name: str
    literals: tuple[str, ...]
    atoms: tuple[str, ...]


class Limit(Exception):
    """The solvability check ran out of states or time."""


# --- reading the single-goal set ----------------------------------------------------------


def distinct_goals(meta: dict[str, Any]) -> list[Single]:
    """The set's goals, one for each set of atoms: repeated goals would make a conjunction
    that asks for less than K goals."""
    seen: dict[frozenset[str], Single] = {}
    for record in meta["records"]:
        atoms = frozenset(record["atoms"])
        if "problem" in record and atoms not in seen:
            seen[atoms] = Single(record["index"], record["goal"], tuple(record["literals"]),
                                 tuple(record["atoms"]))
    return list(seen.values())


def initial_state(folder: Path, meta: dict[str, Any]) -> str:
    """The `(:init ...)` all the set's problems share (a multi-goal problem starts there)."""
    inits = {init_of((folder / r["problem"]).read_text(encoding="utf-8"))
             for r in meta["records"] if "problem" in r}
    if len(inits) != 1:
        raise SystemExit(f"{folder}: the problems start from {len(inits)} initial states, "
                         "a conjunction of their goals has no one start")
    return inits.pop()


def init_of(problem: str) -> str:
    start = problem.index("(:init")
    depth = 0
    for end in range(start, len(problem)):
        depth += {"(": 1, ")": -1}.get(problem[end], 0)
        if depth == 0:
            return problem[start:end + 1]
    raise SystemExit("a problem's (:init ...) is not closed")


# --- writing a problem --------------------------------------------------------------------


def problem_text(domain: str, number: int, goals: Sequence[Single], init: str) -> str:
    atoms = " ".join(dict.fromkeys(a for g in goals for a in g.atoms))
    return (f"; multi-goal {number}: {joined(goals)}\n"
            f"(define (problem {domain}-multi-{number:03d})\n"
            f"  (:domain {domain})\n"
            f"  {init}\n"
            f"  (:goal (and {atoms}))\n"
            f"  (:metric minimize (total-cost)))\n")


def joined(goals: Sequence[Single]) -> str:
    return " & ".join(g.name for g in goals)


def domain_name(domain: str) -> str:
    found = re.search(r"\(define\s+\(domain\s+([^\s)]+)", domain, re.IGNORECASE)
    if not found:
        raise SystemExit("domain.pddl names no domain")
    return found.group(1)


# --- the solvability check ----------------------------------------------------------------


def without_costs(pddl: str) -> str:
    """The text without `:action-costs`: pyperplan reads plain STRIPS."""
    pddl = re.sub(r"\(:functions\s*\(total-cost\)\s*(-\s*number)?\s*\)", "", pddl)
    pddl = re.sub(r"\(increase\s+\(total-cost\)\s+[^()\s]+\s*\)", "", pddl)
    pddl = re.sub(r"\(=\s*\(total-cost\)\s*[^()\s]+\s*\)", "", pddl)
    pddl = re.sub(r"\(:metric\s+minimize\s+\(total-cost\)\s*\)", "", pddl)
    return pddl.replace(":action-costs", "")


def pyperplan_plan(domain: str, problem: str, max_states: int,
                   seconds: float) -> list[str] | None:
    """pyperplan's GBFS plan (IPC steps), None when its search ends with none; Limit when
    it evaluates more than `max_states` states or runs past `seconds`."""
    from pyperplan import grounding
    from pyperplan.heuristics.relaxation import hFFHeuristic
    from pyperplan.pddl.parser import Parser
    from pyperplan.search import greedy_best_first_search

    deadline = time.monotonic() + seconds
    parser = Parser(None, None)
    parser.domInput, parser.probInput = without_costs(domain), without_costs(problem)
    grounded = grounding.ground(parser.parse_problem(parser.parse_domain(False), False))
    estimate = hFFHeuristic(grounded)
    evaluated = 0

    def limited(node: Any) -> float:
        nonlocal evaluated
        evaluated += 1
        if evaluated > max_states or time.monotonic() > deadline:
            raise Limit
        return float(estimate(node))

    found = greedy_best_first_search(grounded, limited)
    return None if found is None else [str(op.name) for op in found]


def verdict(domain: str, problem: str, max_states: int, seconds: float) -> str:
    """"solvable", or why the conjunction is left out."""
    try:
        steps = pyperplan_plan(domain, problem, max_states, seconds)
    except Limit:
        return "no plan within the limits"
    if steps is None:
        return "unsolvable"
    ok, reason, _ = validate(domain, problem, "\n".join(steps))
    return "solvable" if ok else f"pyperplan's plan is invalid: {reason}"


# --- the set ------------------------------------------------------------------------------


@dataclass
class Made:
    records: list[dict[str, Any]]
    texts: dict[str, str]
    rejected: Counter[str]


def make(single: Path, sizes: Sequence[int], count: int, seed: int, max_states: int,
         seconds: float) -> Made:
    meta = json.loads((single / "goals.json").read_text(encoding="utf-8"))
    domain = (single / "domain.pddl").read_text(encoding="utf-8")
    name, init = domain_name(domain), initial_state(single, meta)
    goals = distinct_goals(meta)
    rng = random.Random(seed)
    made = Made([], {}, Counter())
    drawn: set[frozenset[int]] = set()
    for size in sizes:
        if size > len(goals):
            raise SystemExit(f"size {size}: the set has only {len(goals)} distinct goals")
        kept = 0
        for _ in range(MAX_DRAWS * count):
            if kept == count:
                break
            chosen = sorted(rng.sample(goals, size), key=lambda g: g.index)
            key = frozenset(g.index for g in chosen)
            if key in drawn:
                made.rejected["drawn before"] += 1
                continue
            drawn.add(key)
            number = len(made.records)
            text = problem_text(name, number, chosen, init)
            why = verdict(domain, text, max_states, seconds)
            if why != "solvable":
                made.rejected[why] += 1
                continue
            made.records.append(record(number, chosen))
            made.texts[f"p{number:03d}.pddl"] = text
            kept += 1
        if kept < count:
            raise SystemExit(f"size {size}: only {kept} solvable conjunctions in "
                             f"{MAX_DRAWS * count} draws")
    return made


def record(number: int, goals: Sequence[Single]) -> dict[str, Any]:
    return {"index": number, "goal": joined(goals),
            "literals": list(dict.fromkeys(x for g in goals for x in g.literals)),
            "atoms": list(dict.fromkeys(a for g in goals for a in g.atoms)),
            "problem": f"p{number:03d}.pddl", "size": len(goals),
            "single_goals": [g.index for g in goals]}


def write(single: Path, out: Path, made: Made, settings: dict[str, Any]) -> None:
    meta = json.loads((single / "goals.json").read_text(encoding="utf-8"))
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("p[0-9][0-9][0-9].pddl"):
        old.unlink()
    shutil.copyfile(single / "domain.pddl", out / "domain.pddl")
    for file, text in made.texts.items():
        (out / file).write_text(text, encoding="utf-8")
    meta.update(difficulty="multi", goals=len(made.records), records=made.records,
                made_from=single.name, **settings, rejected=dict(made.rejected))
    (out / "goals.json").write_text(json.dumps(meta, indent=1) + "\n", encoding="utf-8")


def sizes_of(text: str) -> list[int]:
    sizes = [int(part) for part in text.split(",") if part.strip()]
    if not sizes or min(sizes) < 2:
        raise argparse.ArgumentTypeError("sizes are whole numbers of at least 2, e.g. 2,3")
    return sizes


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("single", type=Path, help="the single-goal set's folder")
    parser.add_argument("out", type=Path, help="the folder to write the multi-goal set to")
    parser.add_argument("--sizes", type=sizes_of, default=[2, 3],
                        help="goals in a conjunction, comma-separated (default: 2,3)")
    parser.add_argument("--count", type=int, default=20, help="problems for each size")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-states", type=int, default=20000,
                        help="states pyperplan may evaluate for one conjunction")
    parser.add_argument("--time-limit", type=float, default=10.0,
                        help="seconds pyperplan may search for one conjunction")
    args = parser.parse_args(argv)
    made = make(args.single, args.sizes, args.count, args.seed, args.max_states,
                args.time_limit)
    settings = {"sizes": args.sizes, "count": args.count, "seed": args.seed,
                "max_states": args.max_states, "time_limit": args.time_limit}
    write(args.single, args.out, made, settings)
    rejected = ", ".join(f"{n} {why}" for why, n in made.rejected.most_common()) or "none"
    print(f"{args.out}: {len(made.records)} problems (sizes {args.sizes}, {args.count} each, "
          f"seed {args.seed}); rejected: {rejected}")


if __name__ == "__main__":
    main()
