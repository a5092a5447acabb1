"""Generated PDDL is standard: a peer planner (pyperplan) reads it and solves it, and its
plan, replayed on btplan's own models of the same problem, reaches the goal."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.lang import load
from btplan.lang.generators import generate
from btplan.model import instantiate

pyperplan = pytest.importorskip("pyperplan")

SMALL = [("blocksworld", {"blocks": 4}), ("gripper", {"balls": 2}), ("logistics", {"packages": 1})]


@pytest.mark.parametrize(("name", "size"), SMALL)
def test_peer_plan_replays_on_our_models(tmp_path: Path, name: str, size: dict[str, int]) -> None:
    from pyperplan.grounding import ground
    from pyperplan.pddl.parser import Parser
    from pyperplan.search import breadth_first_search

    domain_text, problem_text = generate(name, seed=4, **size)
    (tmp_path / "d.pddl").write_text(domain_text)
    (tmp_path / "p.pddl").write_text(problem_text)
    parser = Parser(str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"))
    peer_task = ground(parser.parse_problem(parser.parse_domain()))
    peer_plan = breadth_first_search(peer_task)
    assert peer_plan, "the peer planner found no plan"

    task = load([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")])
    state = task.initial_state
    for step in peer_plan:
        action_name, *args = step.name.strip("()").split()
        action = instantiate(task.domain.action_map[action_name], tuple(args))
        assert action.applicable(state), step.name
        state = action.apply(state)
    assert all(goal.holds(state) for goal in task.goal_literals)
