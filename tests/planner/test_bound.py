"""The lower bound on plan steps (btplan/planner/bound.py), and plan improvement using it:
LM-cut values worked out by hand, never above the shortest plan, and what a bound that
the plan reaches spares."""

from __future__ import annotations

from collections import deque
from pathlib import Path

import pytest

from btplan.acting.offline import plan
from btplan.model import Task
from btplan.planner import AchieverIndex
from btplan.planner.bound import Cuts, fewest_steps
from btplan.planner.improve import improve
from btplan.planner.neighbourhood import Limits, PlanSpace
from tests.planner.test_classic import validate
from tests.planner.test_improve import gripper, space_of, walk


def bound(pre: list[tuple[int, ...]], add: list[tuple[int, ...]], atoms: int,
          start: list[int], goals: list[int], enough: int = 100, work: int = 10_000) -> int:
    return Cuts(pre, add, atoms).bound(start, goals, enough, work)


def test_a_chain_of_actions_counts_every_step() -> None:
    # 0 -> 1 -> 2 -> 3, one action each
    assert bound([(0,), (1,), (2,)], [(1,), (2,), (3,)], 4, [0], [3]) == 3


def test_goals_that_need_different_actions_add_up_where_h_max_does_not() -> None:
    # h_max of {1, 2} is 1; every plan needs both actions: LM-cut finds two cuts
    assert bound([(0,), (0,)], [(1,), (2,)], 3, [0], [1, 2]) == 2
    # one action making both true is one step
    assert bound([(0,), (0,), (0,)], [(1,), (2,), (1, 2)], 3, [0], [1, 2]) == 1


def test_actions_without_preconditions_and_goals_already_true() -> None:
    assert bound([(), (1,)], [(1,), (2,)], 3, [], [2]) == 2
    assert bound([(0,)], [(1,)], 2, [0, 1], [1]) == 0


def test_unreachable_goals_and_the_caps() -> None:
    assert bound([(0,)], [(1,)], 3, [0], [2], enough=7) == 7  # nothing adds 2
    assert bound([(0,), (1,), (2,)], [(1,), (2,), (3,)], 4, [0], [3], enough=2) == 2
    # three rounds of 6 visits (4 preconditions, 2 start atoms) allowed or not: the
    # bound or none (0 is still a bound)
    chain = ([(0,), (1,), (2,)], [(1,), (2,), (3,)], 4, [0], [3])
    assert bound(*chain, enough=3, work=18) == 3
    assert bound(*chain, enough=3, work=17) == 0


def shortest(task: Task) -> int:
    """Steps of the shortest plan, breadth first over the packed states."""
    space = PlanSpace(AchieverIndex(task, reachable_only=True).packed,
                      frozenset(task.initial_state), task.goal_literals)
    seen, layer, depth = {space.start}, deque([space.start]), 0
    while layer:
        following: deque[int] = deque()
        for state in layer:
            if space.goal(state):
                return depth
            for child in space.generator.successors(state)[1]:
                if child not in seen:
                    seen.add(child)
                    following.append(child)
        layer, depth = following, depth + 1
    raise AssertionError("no plan")


def test_the_bound_never_exceeds_the_shortest_plan(tmp_path: Path) -> None:
    for balls in (1, 2, 3):
        task = gripper(balls=balls, tmp_path=tmp_path)
        relaxed = AchieverIndex(task, reachable_only=True).relaxed
        low = fewest_steps(relaxed, task.initial_state, task.goal_literals, 100)
        assert 0 < low <= shortest(task)


def test_no_bound_where_actions_differ_in_cost(tmp_path: Path) -> None:
    relaxed = AchieverIndex(walk(tmp_path, direct=10), reachable_only=True).relaxed
    task = walk(tmp_path, direct=10)
    assert fewest_steps(relaxed, task.initial_state, task.goal_literals, 5) == 0
    same = walk(tmp_path, direct=1)  # every road costs 1: one step from a to b
    relaxed = AchieverIndex(same, reachable_only=True).relaxed
    assert fewest_steps(relaxed, same.initial_state, same.goal_literals, 5) == 1


def test_a_plan_as_short_as_the_bound_is_not_searched_around(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1)  # every road costs 1, and a to b is one step
    result = plan(task)
    assert [str(a) for a in result.executed] == ["go(a, b)"]
    assert result.stats.shortest and result.stats.removed == 0
    assert not plan(task, improve=False).stats.shortest
    # one ball, the robot in the other room: the bound (3: the relaxed plan never moves
    # back) is below the shortest plan (4), so the plan is not called shortest
    balls = gripper(balls=1, tmp_path=tmp_path)
    result = plan(balls)
    assert len(result.executed) == shortest(balls) == 4
    assert not result.stats.shortest


@pytest.mark.parametrize("balls, floor, shortest", [(2, 5, 5), (4, 10, 11)])
def test_a_floor_near_the_plan_cuts_the_neighbourhood_short(
        tmp_path: Path, balls: int, floor: int, shortest: int) -> None:
    """Two balls (backchained: 7 steps, shortest 5): without a floor the neighbourhood
    grows until it holds every reachable state; with 5 it stops at the first 5-step plan.
    Four balls (backchained: 13 steps, shortest 11): with a floor of 10 the 11-step plan
    is one step above it, and the search around it stops at SLACK_STATES."""
    task = gripper(balls=balls, tmp_path=tmp_path)
    backchained = plan(task, improve=False).executed
    found = improve(space_of(task), backchained, Limits())
    floored = improve(space_of(task), backchained, Limits(), floor=floor)
    assert found is not None and floored is not None
    assert len(found.steps) == len(floored.steps) == shortest
    assert found.complete and not floored.complete
    assert floored.depth < found.depth
    validate(task, floored.steps)
