"""The improved plan in the tree (btplan/acting/offline/improved.py): what `plan` returns executes
the shorter plan from the initial state, the steps shared conditions change nothing of
which step runs, and `--paper` and `improve=False` leave the backchained result as it was."""

from __future__ import annotations

import random
from pathlib import Path

from btplan.acting.offline import load, plan
from btplan.acting.offline.improved import budget, plan_first
from btplan.bt import RUNNING, BehaviorTree, Fallback, Status
from btplan.bt import Sequence as SequenceNode
from btplan.bt.world import LeafKey
from btplan.lang.generators import generate
from btplan.model import Atom, GroundAction, Task
from btplan.planner import AchieverIndex, PlannerOptions, condition_node
from btplan.planner.rescue import plan_alternatives
from tests.planner.shapes import shape
from tests.planner.test_classic import replay, validate


def generated(tmp_path: Path, name: str, seed: int = 0, **size: int) -> Task:
    domain, problem = generate(name, "pddl", seed=seed, **size)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "p.pddl"))


def test_the_tree_executes_the_shorter_plan_it_reports(tmp_path: Path) -> None:
    task = generated(tmp_path, "gripper", balls=2)
    before = plan(task, improve=False)
    after = plan(task)
    assert (len(before.executed), len(after.executed)) == (7, 5)
    validate(task, after.executed)
    assert replay(task, after) == after.executed
    assert after.stats.removed == 2 and after.stats.eliminated == 0
    assert after.stats.actions_executed == 5 and after.stats.cost == 5
    assert after.stats.tree_size == len(after.tree.nodes())
    # the backchained tree is kept, behind the shorter plan's steps
    kept = after.tree.root.children[0].children[0].children[-1]
    assert shape(kept) == shape(before.tree.root)


def test_logistics_plans_get_shorter_and_stay_valid(tmp_path: Path) -> None:
    task = generated(tmp_path, "logistics", packages=3)
    before = plan(task, improve=False)
    after = plan(task)
    assert len(after.executed) < len(before.executed)
    validate(task, after.executed)
    assert replay(task, after) == after.executed


def test_without_improvement_the_backchained_result_stays(tmp_path: Path) -> None:
    task = generated(tmp_path, "gripper", balls=2)
    result = plan(task, improve=False)
    assert result.stats.removed is None
    assert replay(task, result) == result.executed
    assert not any(n.name == "shorter plan first" for n in result.tree.nodes())


def test_the_paper_algorithm_is_never_improved(tmp_path: Path) -> None:
    task = generated(tmp_path, "gripper", balls=2)
    paper = plan(task, options=PlannerOptions.paper())
    again = plan(task, options=PlannerOptions.paper(), improve=False)
    assert PlannerOptions.paper().improve_plan is False
    assert paper.stats.removed is None
    assert [str(a) for a in paper.executed] == [str(a) for a in again.executed]
    assert shape(paper.tree.root) == shape(again.tree.root)


class Probe:
    """A world in a fixed state that reports the first action a tick starts."""

    def __init__(self, state: frozenset[Atom]) -> None:
        self.state = state
        self.started: LeafKey | None = None

    def check(self, key: LeafKey) -> bool:
        return Atom(key[0], tuple(key[1])) in self.state

    def start(self, key: LeafKey) -> Status:
        self.started = self.started or key
        return RUNNING

    def step(self, key: LeafKey) -> Status:
        return RUNNING

    def halt(self, key: LeafKey) -> None:
        pass


def first_action(tree: BehaviorTree, state: frozenset[Atom]) -> LeafKey | None:
    probe = Probe(state)
    tree.tick(probe)
    tree.halt(probe)
    return probe.started


def test_shared_conditions_pick_the_same_step_as_the_flat_alternatives(tmp_path: Path) -> None:
    """In states along the plan and off it (random walks), the tree with shared
    conditions starts the same action as Fallback(goal, flat plan_alternatives)."""
    task = generated(tmp_path, "logistics", packages=3, seed=1)
    steps = plan(task, improve=False).executed
    placeholder = BehaviorTree(SequenceNode([]))
    compact = plan_first(placeholder, task, steps)
    alternatives, _ = plan_alternatives(list(task.goal_literals), steps, task)
    holds = SequenceNode([condition_node(g, task) for g in task.goal_literals])
    flat = BehaviorTree(Fallback([holds, *alternatives]))
    actions = AchieverIndex(task, reachable_only=True).relaxed.actions
    chooser = random.Random(3)
    states = []
    for start in range(len(steps)):
        state = frozenset(task.initial_state)
        for action in steps[:start]:
            state = action.apply(state)
        states.append(state)
        for _ in range(4):  # off the plan: a few random actions
            runnable: list[GroundAction] = [a for a in actions if a.applicable(state)]
            state = chooser.choice(runnable).apply(state)
            states.append(state)
    assert len(compact.nodes()) < sum(len(a.walk()) for a in alternatives)
    picked = [first_action(compact, s) for s in states]
    assert picked == [first_action(flat, s) for s in states]
    assert sum(p is not None for p in picked) > len(steps)  # the probe did see actions


def test_the_budget_is_a_share_of_planning_and_never_past_the_deadline() -> None:
    assert budget(0.0, 0.1, None) == 0.25  # fast planning: the minimum
    assert budget(0.0, 10.0, None) == 2.5  # a quarter of the planning time
    assert budget(0.0, 10.0, 12.0) == 1.0  # half of what is left
    assert budget(0.0, 10.0, 10.5) == 0.0  # under a second left: no improvement
    assert budget(0.0, 10.0, 9.0) == 0.0
