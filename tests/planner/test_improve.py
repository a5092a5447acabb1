"""Plan improvement (btplan/classical/improvement.py): action elimination and plan-neighbourhood
search, on small problems whose best plans are known."""

from __future__ import annotations

import time
from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.lang.generators import generate
from btplan.model import GroundAction, Task
from btplan.planner import AchieverIndex
from btplan.classical.improvement import eliminate, improve
from btplan.classical.neighbourhood import Limits, PlanSpace
from tests.planner.test_classic import validate

WALK = """(define (domain walk)
  (:requirements :typing :action-costs)
  (:types place)
  (:predicates (at ?p - place) (road ?a ?b - place) (seen ?p - place))
  (:functions (total-cost) - number (length ?a ?b - place) - number)
  (:action go
    :parameters (?a ?b - place)
    :precondition (and (at ?a) (road ?a ?b))
    :effect (and (not (at ?a)) (at ?b) (seen ?b) (increase (total-cost) (length ?a ?b)))))
"""
ROADS = """(define (problem roads) (:domain walk)
  (:objects a b c d - place)
  (:init (at a) (road a b) (road b a) (road a c) (road c b) (road b d) (road d b)
         (= (total-cost) 0) (= (length a b) {direct}) (= (length b a) 1)
         (= (length a c) 1) (= (length c b) 1) (= (length b d) 1) (= (length d b) 1))
  (:goal (and (at b)))
  (:metric minimize (total-cost)))
"""


def walk(tmp_path: Path, direct: int) -> Task:
    (tmp_path / "domain.pddl").write_text(WALK)
    (tmp_path / "p.pddl").write_text(ROADS.format(direct=direct))
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "p.pddl"))


def gripper(balls: int = 2, seed: int = 0, tmp_path: Path | None = None) -> Task:
    assert tmp_path is not None
    domain, problem = generate("gripper", "pddl", seed=seed, balls=balls)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "p.pddl"))


def space_of(task: Task) -> PlanSpace:
    models = AchieverIndex(task, reachable_only=True)
    return PlanSpace(models.packed, frozenset(task.initial_state), task.goal_literals)


def steps(task: Task, *names: str) -> list[GroundAction]:
    """`go a c` -> the grounded action go(a, c)."""
    out = []
    for name in names:
        action, *args = name.split()
        out.append(task.instantiate(task.domain.action_map[action], tuple(args)))
    return out


def numbers(space: PlanSpace, plan: list[GroundAction]) -> list[int]:
    encoded = space.encode(plan)
    assert encoded is not None
    return encoded


def test_elimination_drops_a_round_trip_and_keeps_what_the_goal_needs(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)
    space = space_of(task)
    detour = steps(task, "go a b", "go b d", "go d b")
    shorter = eliminate(space, numbers(space, detour))
    assert [str(space.packed.actions[i]) for i in shorter] == ["go(a, b)"]
    # go(a, c) cannot go: without it go(c, b) cannot run and b is never reached
    needed = numbers(space, steps(task, "go a c", "go c b"))
    assert eliminate(space, needed) == needed


def test_a_detour_that_elimination_keeps_is_cut_by_the_neighbourhood(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)
    space = space_of(task)
    found = improve(space, steps(task, "go a c", "go c b"), Limits())
    assert found is not None
    assert [str(a) for a in found.steps] == ["go(a, b)"]
    assert (found.before, found.eliminated, found.searched) == (2, 0, 1)
    validate(task, found.steps)


def test_with_action_costs_the_cheaper_plan_wins_even_when_longer(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=10)
    space = space_of(task)
    found = improve(space, steps(task, "go a b"), Limits())
    assert found is not None
    assert [str(a) for a in found.steps] == ["go(a, c)", "go(c, b)"]
    assert sum(a.cost for a in found.steps) == 2
    validate(task, found.steps)


def test_a_plan_that_is_already_best_is_not_changed(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)
    found = improve(space_of(task), steps(task, "go a b"), Limits())
    assert found is None


def test_backchained_gripper_plan_becomes_the_shortest_one(tmp_path: Path) -> None:
    """Two balls from room a to room b: backchaining carries them one at a time (7
    steps); the shortest plan picks both up, moves once and drops both (5)."""
    task = gripper(tmp_path=tmp_path)
    backchained = plan(task, improve=False).executed
    assert len(backchained) == 7
    space = space_of(task)
    assert eliminate(space, numbers(space, backchained)) == numbers(space, backchained)
    found = improve(space, backchained, Limits())
    assert found is not None and len(found.steps) == 5
    assert found.complete  # every reachable state was looked at: 5 is the least
    validate(task, found.steps)


def test_a_passed_deadline_keeps_what_elimination_found(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)
    space = space_of(task)
    detour = steps(task, "go a c", "go c b", "go b d", "go d b")
    found = improve(space, detour, Limits(deadline=time.perf_counter() - 1))
    assert found is not None
    assert [str(a) for a in found.steps] == ["go(a, c)", "go(c, b)"]
    assert (found.eliminated, found.searched) == (2, 0)


def test_the_neighbourhood_is_bounded_by_its_state_budget(tmp_path: Path) -> None:
    task = gripper(balls=4, tmp_path=tmp_path)
    backchained = plan(task, improve=False).executed
    found = improve(space_of(task), backchained, Limits(max_states=50))
    assert found is None or found.states <= 50
    assert Limits.states_for(10_000) < Limits.states_for(100)


def test_a_plan_with_an_action_outside_the_packed_ones_is_left_alone(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)
    space = space_of(task)
    unknown = GroundAction(name="fly", args=("a", "b"))
    assert space.encode([unknown]) is None
    assert improve(space, [unknown], Limits()) is None
