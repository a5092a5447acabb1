"""The lower bound on plan steps and costs (btplan/classical/bound.py), and plan improvement
using it: LM-cut values worked out by hand, never above the shortest (or cheapest) plan,
and what a bound that the plan reaches spares."""

from __future__ import annotations

import heapq
from collections import deque
from pathlib import Path

import pytest

from btplan.acting.offline import load, plan
from btplan.model import Task
from btplan.planner import AchieverIndex
from btplan.classical.bound import (WORK, Cuts, _cheapest_step, _numbered, fewest_steps,
                                    no_better_plan)
from btplan.classical.improvement import improve
from btplan.classical.neighbourhood import Limits, PlanSpace
from tests.planner.test_classic import validate
from tests.planner.test_improve import gripper, space_of, walk


def bound(pre: list[tuple[int, ...]], add: list[tuple[int, ...]], atoms: int,
          start: list[int], goals: list[int], enough: int = 100, work: int = 10_000,
          costs: list[int] | None = None) -> int:
    return Cuts(pre, add, atoms).bound(start, goals, enough, work, costs)


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


RW = Path(__file__).resolve().parents[2] / "bench" / "problems" / "btpg_rw_single"


def best(task: Task) -> tuple[float, int]:
    """(cost, steps) of the best plan as improve.py weighs plans (cost, then steps):
    Dijkstra over the packed states, with only the actions relevant to the goal (those
    that add a goal or a precondition of a relevant action). Without negative
    preconditions that loses no best plan: leaving an irrelevant action out of a plan
    only leaves deletes out, and what it adds nothing later needs."""
    space = PlanSpace(AchieverIndex(task, reachable_only=True).packed,
                      frozenset(task.initial_state), task.goal_literals)
    actions = space.packed.actions
    assert all(p.positive for a in actions for p in a.preconditions)
    wanted = {g.atom for g in task.goal_literals}
    relevant: set[int] = set()
    while True:
        more = {i for i, a in enumerate(actions) if wanted.intersection(a.add)} - relevant
        if not more:
            break
        relevant |= more
        wanted.update(p.atom for i in more for p in actions[i].preconditions)
    done: set[int] = set()
    queue = [((0.0, 0), space.start)]
    while queue:
        (cost, steps), state = heapq.heappop(queue)
        if state in done:
            continue
        done.add(state)
        if space.goal(state):
            return cost, steps
        for i, child in zip(*space.generator.successors(state), strict=True):
            if i in relevant and child not in done:
                heapq.heappush(queue, ((cost + space.costs[i], steps + 1), child))
    raise AssertionError("no plan")


def test_costs_cut_by_the_cheapest_action_of_each_landmark() -> None:
    # a chain costing 2, 3 and 4
    assert bound([(0,), (1,), (2,)], [(1,), (2,), (3,)], 4, [0], [3], costs=[2, 3, 4]) == 9
    # one action of 10 to the goal, or two of 1 through atom 1: the cheaper way counts
    assert bound([(0,), (0,), (1,)], [(2,), (1,), (2,)], 3, [0], [2], costs=[10, 1, 1]) == 2
    # two goals, each its own action: the costs add up; an action costing nothing adds 0
    assert bound([(0,), (0,)], [(1,), (2,)], 3, [0], [1, 2], costs=[3, 5]) == 8
    assert bound([(0,), (1,)], [(1,), (2,)], 3, [0], [2], costs=[0, 4]) == 4


def test_a_plan_the_bound_proves_best_is_not_improved_and_is_best(tmp_path: Path) -> None:
    """Roads of different costs: a to b directly costs 2, through c two roads of 1.
    The direct road is the plan, LM-cut with costs says 2 and with steps 1, so
    improvement is skipped, and no plan is cheaper, nor as cheap in fewer steps."""
    task = walk(tmp_path, direct=2)
    result = plan(task)
    assert [str(a) for a in result.executed] == ["go(a, b)"]
    assert result.stats.shortest and result.stats.removed == 0
    assert (result.stats.cost, len(result.executed)) == best(task) == (2.0, 1)


def test_the_bound_does_not_skip_a_plan_that_can_be_bettered(tmp_path: Path) -> None:
    relaxed = AchieverIndex(walk(tmp_path, direct=10), reachable_only=True).relaxed
    task = walk(tmp_path, direct=10)
    start, goal = task.initial_state, task.goal_literals
    assert not no_better_plan(relaxed, start, goal, 1, 10.0)  # through c costs 2
    # the cheapest plan, but the direct road is one step: both bounds must be reached,
    # so this best plan is not proven best (improvement runs, and finds nothing)
    assert not no_better_plan(relaxed, start, goal, 2, 2.0)
    result = plan(task)
    assert (result.stats.cost, len(result.executed)) == best(task) == (2.0, 2)
    # as cheap, but a step more than the direct road of 2: not proven best
    task = walk(tmp_path, direct=2)
    relaxed = AchieverIndex(task, reachable_only=True).relaxed
    assert not no_better_plan(relaxed, task.initial_state, task.goal_literals, 2, 2.0)
    assert no_better_plan(relaxed, task.initial_state, task.goal_literals, 1, 2.0)


def test_no_proof_where_costs_are_not_whole_numbers(tmp_path: Path) -> None:
    task = walk(tmp_path, direct=1.5)  # type: ignore[arg-type]
    relaxed = AchieverIndex(task, reachable_only=True).relaxed
    assert not no_better_plan(relaxed, task.initial_state, task.goal_literals, 1, 1.5)
    assert not plan(task).stats.shortest


@pytest.mark.parametrize("name", ["p001", "p004", "p012", "p039"])
def test_robowaiter_plans_the_bound_proves_best_are_best(name: str) -> None:
    """BTPG's RoboWaiter goals, whose plans (1 to 5 steps, costs 3 to 15 each) the
    bound proves best: so they are, by a search over every state."""
    task = load(str(RW / "domain.pddl"), str(RW / f"{name}.pddl"))
    result = plan(task)
    assert result.stats.shortest and result.stats.removed == 0
    assert (result.stats.cost, len(result.executed)) == best(task)
    validate(task, result.executed)


@pytest.mark.parametrize("name", ["p004", "p012", "p039"])
def test_the_goals_relevant_actions_bound_as_the_whole_model(name: str) -> None:
    """LM-cut over the actions relevant to the goal (what no_better_plan computes) is
    LM-cut over the whole model, with the actions' costs and with steps: it proves a
    plan of exactly the whole model's bounds best, and none of a step or a unit more."""
    task = load(str(RW / "domain.pddl"), str(RW / f"{name}.pddl"))
    relaxed = AchieverIndex(task).relaxed
    ids, pre, add = relaxed.numbered()
    start = [ids[a] for a in task.initial_state if a in ids]
    goals = [ids[g.atom] for g in task.goal_literals]
    costs = [int(c) for c in relaxed.action_costs()]
    cost = Cuts(pre, add, len(ids)).bound(start, goals, 1000, 10**9, costs)
    steps = Cuts(pre, add, len(ids)).bound(start, goals, 1000, 10**9)
    assert cost > steps > 0 and len(relaxed.actions) > 100
    args = (relaxed, task.initial_state, task.goal_literals)
    assert no_better_plan(*args, steps, float(cost))
    assert not no_better_plan(*args, steps + 1, float(cost))
    assert not no_better_plan(*args, steps, float(cost + 1))


@pytest.mark.parametrize("name", ["p000", "p001", "p002", "p003"])
def test_a_step_of_the_cheapest_achiever_is_answered_as_the_rounds_answer(name: str) -> None:
    """A plan of one step as cheap as the cheapest achiever of a false goal is proven
    best without LM-cut's rounds, as the rounds prove it; a unit cheaper, it is not."""
    task = load(str(RW / "domain.pddl"), str(RW / f"{name}.pddl"))
    relaxed = AchieverIndex(task).relaxed
    start, goal = task.initial_state, task.goal_literals
    ids, adders, costs = relaxed.numbered()[0], relaxed.adders(), relaxed.action_costs()
    false = [ids[g.atom] for g in goal if g.positive and g.atom not in start]
    cheapest = max(min(costs[i] for i in adders[at]) for at in false)
    assert _cheapest_step(relaxed, start, goal, cheapest, WORK)
    assert not _cheapest_step(relaxed, start, goal, cheapest + 1, WORK)
    found = _numbered(relaxed, start, goal)
    assert found is not None
    cuts, numbers, goals, kept = found
    assert cuts.bound(numbers, goals, int(cheapest), WORK, [int(costs[i]) for i in kept]) >= cheapest
    assert cuts.bound(numbers, goals, 1, WORK) >= 1
    assert no_better_plan(relaxed, start, goal, 1, cheapest)
    assert not _cheapest_step(relaxed, start, goal, cheapest, 10)  # the rounds' work too
