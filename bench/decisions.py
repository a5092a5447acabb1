"""Which action btplan and replanning start in each state they meet, and where they differ.

A failed run's cause (btplan.sweep.explain) compares it with one reference run of the
same seed. Two executors that meet different states face the same disturbance
decisions at different moments, so one reaching the goal and the other not may say
more about timing than about either. This script asks the question the cause cannot:
in the states both meet, do they decide alike? It runs `btplan` and `replan` on the
same seeds and prints each state (facts that actions and agents change) in which the
two started different actions, with how often each did. A state one executor meets
only while an action of its own keeps running (the robot placing the cube at the goal)
is counted where it starts an action there.

Run:  python bench/decisions.py [--scenario obstacle] [--rate 0.3] [--seeds 0:40]
"""

from __future__ import annotations

import argparse
from collections import Counter, defaultdict
from collections.abc import Sequence
from typing import Any

from btplan import acting
from btplan.acting.config import ActingConfig
from btplan.baselines import run_baseline
from btplan.sweep.runs import Job, prepared
from btplan.worlds.symbolic import SymbolicWorld

FILES = {"obstacle": "domains/pick_place_obstacle.bt",
         "towers": "bench/problems/blocksworld_6.bt",
         "packages": "bench/problems/logistics_1.bt"}

Decisions = defaultdict[frozenset[str], Counter[str]]


def watch(world: Any, static: frozenset[str], into: Decisions) -> None:
    """Count, per state, the actions `world` is asked to start."""
    start = world.start

    def counted(key: tuple[str, tuple[str, ...]]) -> Any:
        state = frozenset(str(a) for a in world.facts()) - static
        into[state][f"{key[0]}({', '.join(key[1])})"] += 1
        return start(key)

    world.start = counted


def decide(job: Job, rate: float, seeds: range) -> dict[str, Decisions]:
    task, scenario, max_ticks = prepared(job)
    changed = {e.predicate for a in task.domain.actions for e in a.effects}
    static = frozenset(str(a) for a in task.initial_state if a.predicate not in changed)
    seen: dict[str, Decisions] = {m: defaultdict(Counter) for m in ("btplan", "replan")}
    config = ActingConfig.algorithm1(name="look-ahead", expansions_per_tick=64,
                                     expand_later_preconditions=True,
                                     skip_moved_while_held=True, retry_failed_actions=True)
    for seed in seeds:
        for method, decisions in seen.items():
            world = SymbolicWorld(task, seed=seed)
            watch(world, static, decisions)
            agents = scenario.agents(task, rate, seed)
            if method == "replan":
                run_baseline(task, world, agents, method, max_ticks)
            else:
                acting.run(task, agents=agents, world=world, seed=seed, max_ticks=max_ticks,
                           config=config)
    return seen


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--scenario", default="obstacle", choices=sorted(FILES))
    parser.add_argument("--rate", type=float, default=0.3)
    parser.add_argument("--seeds", default="0:40", help="first:last (last excluded)")
    args = parser.parse_args(argv)
    first, last = (int(x) for x in args.seeds.split(":"))
    seen = decide(Job((FILES[args.scenario],), args.scenario), args.rate, range(first, last))
    mine, theirs = seen["btplan"], seen["replan"]
    both = [s for s in mine if s in theirs]
    differ = [s for s in both if set(mine[s]) != set(theirs[s])]
    print(f"states where both started an action: {len(both)}; deciding differently: "
          f"{len(differ)}; met by btplan only: {len(set(mine) - set(theirs))}, "
          f"by replan only: {len(set(theirs) - set(mine))}")
    for state in sorted(differ, key=sorted):
        print("  " + ", ".join(sorted(state)))
        print(f"    btplan: {dict(mine[state])}\n    replan: {dict(theirs[state])}")
    for name, one, other in (("btplan", mine, theirs), ("replan", theirs, mine)):
        for state in sorted(set(one) - set(other), key=sorted):
            print(f"  only {name}: " + ", ".join(sorted(state)) + f" -> {dict(one[state])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
