"""What large problems need from the hot paths, on small cases.

h_add and relaxed reachability on integer-encoded atoms must give the values of a
plain reference computation; the bindings that can run now must survive the cap on
enumerated bindings; achievers only reachable through what the branch pursues are
recognised at any depth.
"""

from __future__ import annotations

import heapq
import math
import random
from dataclasses import replace
from pathlib import Path

import pytest

from btplan.lang import load as load_paths
from btplan.lang.generators import generate
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.planner.expand import not_through_pursued
from btplan.classical.heuristic import RelaxedModel


def task_of(tmp_path: Path, name: str, seed: int, **size: int) -> Task:
    domain, problem = generate(name, seed=seed, **size)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    return load_paths([str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl")])


def reference_costs(model: RelaxedModel, state: frozenset[Atom]) -> dict[Atom, float]:
    """h_add by rounds of relaxation until nothing improves: slow, but plainly right."""
    cost = {a: 0.0 for a in state}
    changed = True
    while changed:
        changed = False
        for action in model.actions:
            pre = {p.atom for p in action.preconditions if p.positive}
            if all(p in cost for p in pre):
                value = sum(cost[p] for p in pre) + action.cost
                for atom in action.add:
                    if value < cost.get(atom, math.inf):
                        cost[atom] = value
                        changed = True
    return cost


def reference_reachable(model: RelaxedModel, state: frozenset[Atom],
                        avoided: set[Atom]) -> set[Atom]:
    reached = set(state) - avoided
    queue = list(reached)
    heapq.heapify(queue)
    changed = True
    while changed:
        changed = False
        for action in model.actions:
            pre = {p.atom for p in action.preconditions if p.positive}
            if pre <= reached and not pre & avoided:
                fresh = set(action.add) - reached - avoided
                if fresh:
                    reached |= fresh
                    changed = True
    return reached


@pytest.mark.parametrize(("name", "size"), [("blocksworld", {"blocks": 5}),
                                            ("gripper", {"balls": 3}),
                                            ("logistics", {"packages": 2})])
@pytest.mark.parametrize("levels", [True, False])
def test_h_add_and_reachability_match_a_reference(
        tmp_path: Path, name: str, size: dict[str, int], levels: bool) -> None:
    task = task_of(tmp_path, name, 1, **size)
    model = RelaxedModel(task)
    assert model._integral  # unit costs: one bucket per value unless told otherwise
    model._integral = levels  # the heap, used when some action cost is fractional
    rng = random.Random(3)
    state = task.initial_state
    atoms = sorted({a for action in model.actions for a in action.add})
    for _ in range(6):
        costs = model.costs(state)
        reference = reference_costs(model, state)
        assert costs == reference and dict(costs) == reference
        assert all(costs.get(a) == reference.get(a) and (a in costs) == (a in reference)
                   for a in atoms)
        avoided = set(rng.sample(atoms, 2))
        reached = reference_reachable(model, state, avoided)
        targets = rng.sample(atoms, 5)
        assert model.reachable_avoiding(state, avoided, targets) == set(targets) & reached
        assert model.reachable(state, targets) == (
            set(targets) <= reference_reachable(model, state, set()))
        runnable = [a for a in model.actions if a.applicable(state)]
        state = rng.choice(runnable).apply(state)


def test_the_binding_that_can_run_now_survives_the_cap(tmp_path: Path) -> None:
    # 12 blocks: names sort b1, b10, b11, b12, b2, ...; the block on top of the one to
    # clear may sort last, and only three bindings are enumerated.
    task = task_of(tmp_path, "blocksworld", 0, blocks=12)
    index = AchieverIndex(task, replace(PlannerOptions(), max_bindings=3))
    state = task.initial_state
    tops = [a for a in state if a.predicate == "on"]
    assert tops
    for top in tops:
        above, below = top.args
        found = index.achievers(GroundLiteral(Atom("clear", (below,)), True), state, None, 50)
        assert f"unstack({above}, {below})" in [str(a) for a in found]


def test_an_achiever_needing_what_it_is_for_is_recognised_two_steps_deep(
        tmp_path: Path) -> None:
    task = task_of(tmp_path, "blocksworld", 0, blocks=4)
    state = task.initial_state
    table = sorted(a.args[0] for a in state if a.predicate == "on_table")
    block = table[0]
    other = next(b for b in sorted(task.object_types) if b != block)
    index = AchieverIndex(task)
    holding = GroundLiteral(Atom("holding", (block,)), True)
    unstack = index.ground(next(t for t in task.domain.actions if t.name == "unstack"),
                           (block, other))
    pick_up = index.ground(next(t for t in task.domain.actions if t.name == "pick_up"),
                           (block,))
    # block is on the table: on(block, other) needs holding(block), the goal itself.
    kept = not_through_pursued([unstack, pick_up], {holding}, index.relaxed, state,
                               task.object_types)
    assert kept == [pick_up]
    assert not_through_pursued([unstack, pick_up], set(), index.relaxed, state,
                               task.object_types) == [unstack, pick_up]


def test_the_binding_nearest_to_running_survives_the_cap(tmp_path: Path) -> None:
    # To clear a block under a covered one: unstack(above, below) is a step away (clear
    # `above` first), every clear block elsewhere holds one precondition now too, and
    # only one binding is enumerated. Counting what holds now cannot tell them apart.
    task = task_of(tmp_path, "blocksworld", 2, blocks=12)
    index = AchieverIndex(task, replace(PlannerOptions(), max_bindings=1))
    state = task.initial_state
    covered = {a.args[1] for a in state if a.predicate == "on"}
    buried = [a for a in state if a.predicate == "on" and a.args[0] in covered]
    assert buried
    for top in buried:
        above, below = top.args
        found = index.achievers(GroundLiteral(Atom("clear", (below,)), True), state, None, 50)
        assert f"unstack({above}, {below})" in [str(a) for a in found]
