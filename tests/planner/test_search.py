"""The last resort: a stuck condition planned by search, its plan made a subtree.

Small cases only: the search on its own, the plan as a reactive subtree ticked in the
symbolic world, achievers whose preconditions exclude each other, and Sussman's
anomaly solved by the rescue where backchaining alone stops.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from btplan.acting.offline import load, plan
from btplan.bt import SUCCESS, BehaviorTree, Fallback
from btplan.bt import Sequence as SequenceNode
from btplan.errors import PlanningError
from btplan.lang import load as load_paths
from btplan.lang.generators import generate
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex, PlannerOptions
from btplan.planner.expand import condition_node
from btplan.planner.rescue import plan_alternatives, regress
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS
from tests.planner.test_classic import replay, validate


def literal(text: str, positive: bool = True) -> GroundLiteral:
    name, _, rest = text.partition("(")
    args = tuple(a.strip() for a in rest.rstrip(")").split(",") if a.strip())
    return GroundLiteral(Atom(name, args), positive)


def blocks(tmp_path: Path, count: int, seed: int) -> Task:
    domain, problem = generate("blocksworld", seed=seed, blocks=count)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    return load_paths([str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl")])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_search_finds_a_plan_that_reaches_the_goal(tmp_path: Path, seed: int) -> None:
    task = blocks(tmp_path, 6, seed)
    engine = AchieverIndex(task).subgoal_search
    steps = engine.search(task.initial_state, task.goal_literals)
    assert steps is not None
    validate(task, steps)


def test_kept_conditions_hold_at_every_step_or_there_is_no_plan() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))  # c on a; a and b on the table
    engine = AchieverIndex(task).subgoal_search
    start = task.initial_state
    goal = [literal("on(b, c)")]
    free = engine.search(start, goal)
    assert free is not None and [str(a) for a in free] == ["pickup(b)", "stack(b, c)"]
    # Keeping on(c, a) forbids nothing this plan does; keeping clear(c) forbids stacking.
    assert engine.search(start, goal, keep=[literal("on(c, a)")]) == free
    assert engine.search(start, goal, keep=[literal("clear(c)")]) is None
    # a cannot be on b while c stays on a.
    assert engine.search(start, [literal("on(a, b)")], keep=[literal("on(c, a)")]) is None
    assert engine.search(start, [literal("on(a, b)")]) is not None


def test_an_unreachable_goal_has_no_plan() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    engine = AchieverIndex(task).subgoal_search
    assert engine.search(task.initial_state, [literal("on(a, a)")]) is None


def test_regression_drops_what_a_step_achieves_and_adds_its_preconditions() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    engine = AchieverIndex(task).subgoal_search
    goal = [literal("on(b, c)")]
    steps = engine.search(task.initial_state, goal)
    assert steps is not None
    needed = regress(goal, steps)
    assert len(needed) == len(steps)
    # Before the last step (stack(b, c)) its preconditions are needed, not on(b, c).
    assert set(needed[-1]) == set(steps[-1].preconditions)
    state = task.initial_state
    for before, step in zip(needed, steps, strict=True):
        assert all(g.holds(state) for g in before)  # each holds where the plan is
        state = step.apply(state)


def test_the_plan_subtree_reaches_the_goal_and_skips_steps_already_done(
        tmp_path: Path) -> None:
    task = blocks(tmp_path, 5, 1)
    engine = AchieverIndex(task).subgoal_search
    goal = list(task.goal_literals)
    steps = engine.search(task.initial_state, goal)
    assert steps is not None and len(steps) >= 3
    for skipped in (0, 2):
        world = SymbolicWorld(task)
        for step in steps[:skipped]:
            world.apply_action(step)  # someone else did the first steps
        alternatives, _ = plan_alternatives(goal, steps, task)
        checks = [condition_node(g, task) for g in goal]
        tree = BehaviorTree(Fallback([SequenceNode(checks), *alternatives]))
        for _ in range(len(steps)):  # one step a tick (each returns SUCCESS as it ends)
            if all(g.holds(world.facts()) for g in goal):
                break
            assert tree.tick(world) is SUCCESS
        assert all(g.holds(world.facts()) for g in goal)
        assert [str(a) for a in world.executed] == [str(a) for a in steps[skipped:]]


HANDS = """
(define (domain bar) (:requirements :strips :typing)
  (:types hand glass)
  (:predicates (holding ?h - hand ?g - glass) (empty ?h - hand) (full ?g - glass)
               (ontable ?g - glass))
  (:action grasp :parameters (?h - hand ?g - glass)
    :precondition (and (empty ?h) (ontable ?g))
    :effect (and (not (empty ?h)) (not (ontable ?g)) (holding ?h ?g)))
  (:action fill :parameters (?g - glass ?h1 - hand ?h2 - hand)
    :precondition (and (holding ?h1 ?g) (empty ?h2))
    :effect (full ?g)))
"""


def test_achievers_whose_preconditions_exclude_each_other_are_dropped(tmp_path: Path) -> None:
    (tmp_path / "bar.pddl").write_text(HANDS)
    (tmp_path / "p.pddl").write_text("""(define (problem one) (:domain bar)
      (:objects left right - hand g - glass)
      (:init (empty left) (empty right) (ontable g)) (:goal (full g)))""")
    task = load_paths([str(tmp_path / "bar.pddl"), str(tmp_path / "p.pddl")])
    state = task.initial_state
    full = literal("full(g)")
    kept = AchieverIndex(task).achievers(full, state, None, 8)
    # holding(left, g) and empty(left) never hold together: fill(g, left, left) never runs.
    assert sorted(str(a) for a in kept) == ["fill(g, left, right)", "fill(g, right, left)"]
    blind = AchieverIndex(task, PlannerOptions(mutexes=False)).achievers(full, state, None, 8)
    assert "fill(g, left, left)" in {str(a) for a in blind}


def test_sussman_is_rescued_by_search_where_backchaining_alone_stops() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    # In the listed goal order, without goal reordering and backtracking, backchaining
    # finds no conflict-free place.
    alone = PlannerOptions(reorder_goals=False, backtrack=False, search_stuck=False,
                           goal_agenda=False)
    with pytest.raises(PlanningError, match="no conflict-free place"):
        plan(task, options=alone)
    rescued = plan(task, options=replace(alone, search_stuck=True))
    assert rescued.stats.searches >= 1
    validate(task, rescued.executed)
    assert replay(task, rescued) == rescued.executed


def test_the_paper_mode_never_searches() -> None:
    assert PlannerOptions.paper().search_stuck is False
    task = load(str(DOMAINS / "planner_sussman.bt"))
    with pytest.raises(PlanningError):
        plan(task, options=PlannerOptions.paper())
