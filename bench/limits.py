"""Whether `btplan plan --timeout` holds, and how much memory it takes, on wide problems.

A wide problem has many objects and a short plan: gripper with N balls in room a and
one ball wanted in room b (pick, move, drop). Both planners run as whole processes on
the same PDDL files; btplan with `--timeout T`, pyperplan (GBFS with h_FF) killed at T.
The table gives each one's wall seconds, exit, and peak RSS; for btplan also how far
past the limit it ended (the target: within 10% of T, or 0.5 s).

Then `btplan sweep --timeout T` on runs that all go past T: one run's wall time.

Last, what the limit itself changes: with one, the whole-goal search may take turns from
backchaining (btplan/acting/offline/whole_goal.py), with `--timeout 0` it never does.
Generated blocksworld (seed 0) runs at the default limit and with `--timeout 0`: wall
time, peak RSS and validated plan length of each (the target: 200 blocks within 60 s and
300 MB either way, and not slower with the turns than without).

    python bench/limits.py                      # N = 10^2 .. 10^5, T = 5 s
    python bench/limits.py --sizes 100 1000 --timeout 2
    python bench/limits.py --only-turns --turns-blocks 120 200
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from corpus import command, measure  # noqa: E402  (the whole-process runner, shared)

DOMAIN = """(define (domain gripper)
  (:requirements :strips :typing)
  (:types room ball gripper)
  (:predicates (at-robby ?r - room) (at ?b - ball ?r - room) (free ?g - gripper)
               (carry ?b - ball ?g - gripper))
  (:action move :parameters (?from ?to - room)
    :precondition (at-robby ?from)
    :effect (and (at-robby ?to) (not (at-robby ?from))))
  (:action pick :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (at ?b ?r) (at-robby ?r) (free ?g))
    :effect (and (carry ?b ?g) (not (at ?b ?r)) (not (free ?g))))
  (:action drop :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (carry ?b ?g) (at-robby ?r))
    :effect (and (at ?b ?r) (free ?g) (not (carry ?b ?g)))))
"""


def problem(balls: int) -> str:
    names = " ".join(f"b{i}" for i in range(balls))
    at = " ".join(f"(at b{i} a)" for i in range(balls))
    return (f"(define (problem wide-{balls}) (:domain gripper)\n"
            f"  (:objects a b - room left right - gripper {names} - ball)\n"
            f"  (:init (at-robby a) (free left) (free right) {at})\n"
            "  (:goal (at b0 b)))\n")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[100, 1000, 10_000, 100_000])
    parser.add_argument("--timeout", type=float, default=5.0)
    parser.add_argument("--sweep-size", type=int, default=100_000,
                        help="balls of the problem the sweep's runs go past the limit on")
    parser.add_argument("--turns-blocks", type=int, nargs="*", default=[200],
                        help="blocks of the generated problems run with and without the "
                             "search's turns (none: skip)")
    parser.add_argument("--only-turns", action="store_true",
                        help="only the runs with and without the turns")
    args = parser.parse_args(argv)
    if args.only_turns:
        return 0 if search_turns(args.turns_blocks) else 1
    limit = args.timeout
    print(f"gripper, N balls in room a, goal: one ball in room b; --timeout {limit:g} s")
    print(f"{'N':>7} | {'btplan s':>8} {'exit':>4} {'past T':>6} {'peak MB':>8} | "
          f"{'pyperplan s':>11} {'exit':>4} {'peak MB':>8}")
    held = True
    with tempfile.TemporaryDirectory() as work:
        folder = Path(work)
        domain = folder / "domain.pddl"
        domain.write_text(DOMAIN)
        for balls in args.sizes:
            task = folder / f"p{balls}.pddl"
            task.write_text(problem(balls))
            cells = []
            for planner in ("btplan", "pyperplan"):
                argv_ = command(planner, domain, task, str(folder / "plan.txt"), limit)
                code, seconds, rss, _ = measure(argv_, limit + 30 if planner == "btplan"
                                                else limit, work)
                cells.append((code, seconds, rss))
            (code, seconds, rss), (p_code, p_seconds, p_rss) = cells
            past = seconds - limit
            held &= past <= max(0.1 * limit, 0.5)
            print(f"{balls:>7} | {seconds:>8.2f} {str(code):>4} {past:>+6.2f} {rss:>8.1f} | "
                  f"{p_seconds:>11.2f} {'kill' if p_code is None else p_code:>4} "
                  f"{p_rss:>8.1f}")
        held &= sweep_timeouts(folder, domain, args.sweep_size, limit)
    print(f"--timeout held within 10% or 0.5 s on every size: {'yes' if held else 'no'}")
    if args.turns_blocks:
        search_turns(args.turns_blocks)
    return 0


DEFAULT_LIMIT = 300.0
"""`btplan plan`'s default --timeout."""

TURNS_TARGET = (200, 60.0, 300.0)
"""Blocks, seconds and MB: the problem the target names, and its bounds."""


def search_turns(sizes: list[int]) -> bool:
    """Generated blocksworld at the default limit (the search's turns on) and with
    `--timeout 0` (off): seconds, peak MB and steps each; whether the target is met."""
    from validate_plan import validate

    from btplan.lang.generators import generate

    print(f"\nblocksworld, seed 0: `btplan plan` at the default {DEFAULT_LIMIT:g} s limit "
          "(the search's turns on) and with --timeout 0 (off)")
    print(f"{'blocks':>6} | {'turns on: s':>11} {'peak MB':>8} {'steps':>5} | "
          f"{'off: s':>7} {'peak MB':>8} {'steps':>5}")
    met = True
    with tempfile.TemporaryDirectory() as work:
        folder = Path(work)
        for blocks in sizes:
            domain_text, problem_text = generate("blocksworld", "pddl", seed=0, blocks=blocks)
            domain, task = folder / "domain.pddl", folder / f"bw{blocks}.pddl"
            domain.write_text(domain_text)
            task.write_text(problem_text)
            cells = []
            for limit in (DEFAULT_LIMIT, 0.0):
                plan = folder / "plan.txt"
                plan.unlink(missing_ok=True)
                code, seconds, rss, _ = measure(
                    command("btplan", domain, task, str(plan), limit), DEFAULT_LIMIT + 60, work)
                ok = code == 0 and plan.exists() and validate(
                    domain_text, problem_text, plan.read_text())[0]
                steps = (len([x for x in plan.read_text().splitlines()
                              if x.strip() and not x.startswith(";")]) if ok else None)
                cells.append((seconds, rss, steps))
            (on_s, on_mb, on_steps), (off_s, off_mb, off_steps) = cells
            print(f"{blocks:>6} | {on_s:>11.1f} {on_mb:>8.0f} {on_steps or '-'!s:>5} | "
                  f"{off_s:>7.1f} {off_mb:>8.0f} {off_steps or '-'!s:>5}")
            target, seconds_max, mb_max = TURNS_TARGET
            if blocks == target:
                met = (on_steps is not None and off_steps is not None
                       and max(on_s, off_s) <= seconds_max and max(on_mb, off_mb) <= mb_max
                       and on_s <= 1.1 * off_s + 1.0)
                print(f"target: {target} blocks within {seconds_max:g} s and {mb_max:g} MB "
                      f"with the turns and without, and not slower with them (10%, 1 s): "
                      f"{'met' if met else 'missed'}")
    return met


def sweep_timeouts(folder: Path, domain: Path, balls: int, limit: float) -> bool:
    """`btplan sweep --timeout` cuts each run: two sweeps of runs that all go past the
    limit, of 2 and of 4 runs, one worker; the difference over 2 is one run's wall time,
    without the sweep's own start and end."""
    task = folder / f"p{balls}.pddl"
    task.write_text(problem(balls))
    times = []
    for runs in (2, 4):
        argv = [sys.executable, "-m", "btplan", "sweep", str(domain), str(task), "--seeds",
                f"0:{runs}", "--rates", "0", "--method", "btplan", "--jobs", "1", "--timeout",
                f"{limit:g}", "-o", str(folder / "rows.csv"), "-q"]
        code, seconds, _, _ = measure(argv, runs * limit + 60, str(folder))
        assert code == 1, f"every run should end at the limit (exit {code})"
        times.append(seconds)
    per_run = (times[1] - times[0]) / 2
    past = per_run - limit
    print(f"sweep --timeout {limit:g} s, {balls} balls, one worker: {per_run:.2f} s a run "
          f"({past:+.2f} s past the limit)")
    return past <= max(0.1 * limit, 0.5)


if __name__ == "__main__":
    raise SystemExit(main())
