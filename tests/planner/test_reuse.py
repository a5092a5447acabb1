"""Models kept with the domain for later planning calls (btplan/planner/reuse.py): a
call finds what an earlier one built where its task agrees on what the model depends
on, and plans as it would have alone."""

from __future__ import annotations

from pathlib import Path

from btplan.acting.offline import PlanResult, load, plan
from btplan.model import Atom, Literal, Task
from btplan.planner import AchieverIndex
from btplan.records import replace

ROOT = Path(__file__).resolve().parents[2]
RW = ROOT / "bench" / "problems" / "btpg_rw_single"


def robowaiter(*names: str) -> list[Task]:
    """Goals of one domain object (as an acting run's plans are), domain read once."""
    first, *rest = [load(str(RW / "domain.pddl"), str(RW / f"{n}.pddl")) for n in names]
    return [first, *(Task(domain=first.domain, problem=t.problem) for t in rest)]


def shape(result: PlanResult) -> tuple[list[str], list[tuple[str, str]], float]:
    """What planning made: the plan, the tree's nodes in order, the cost."""
    nodes = [(type(n).__name__, n.name) for n in result.tree.nodes()]
    return [str(a) for a in result.executed], nodes, result.stats.cost


def with_init(task: Task, atoms: list[Atom]) -> Task:
    init = tuple(Literal(predicate=a.predicate, args=a.args) for a in atoms)
    return Task(domain=task.domain, problem=replace(task.problem, init=init))


def test_later_calls_plan_as_they_would_alone() -> None:
    """Each goal planned after the others of the same domain object, and planned again,
    gives the tree and plan it gets with a domain of its own."""
    names = ["p004", "p012", "p039", "p000", "p012"]
    shared = robowaiter(*names)
    for name, task in zip(names, shared, strict=True):
        alone = load(str(RW / "domain.pddl"), str(RW / f"{name}.pddl"))
        assert shape(plan(task)) == shape(plan(alone)), name


def test_what_a_model_depends_on_decides_whether_it_is_reused() -> None:
    """Two goals of one problem share the relaxed model and the mutexes; another initial
    state with the same static facts shares the relaxed model but not the mutexes; the
    same problem read again (another domain object) shares nothing."""
    first, second = robowaiter("p004", "p012")
    index = AchieverIndex(first)
    assert AchieverIndex(second).relaxed is index.relaxed
    assert AchieverIndex(second).mutexes is index.mutexes
    moved = with_init(first, [*(a for a in first.initial_state if a.predicate != "robotnear"),
                              Atom("robotnear", ("table1",))])
    assert AchieverIndex(moved).relaxed is index.relaxed
    assert AchieverIndex(moved).mutexes is not index.mutexes
    again = load(str(RW / "domain.pddl"), str(RW / "p004.pddl"))
    assert AchieverIndex(again).relaxed is not index.relaxed
    # grounded by reachability from the initial state: a model of its own
    assert AchieverIndex(first, reachable_only=True).relaxed is not index.relaxed


def test_a_plan_from_another_state_of_the_same_domain_is_right() -> None:
    """Planned from a state where the robot holds something (a replan in a run), with
    the models the first plan built: the plan runs from that state, reaches the goal,
    and is the one planned with a domain of its own."""
    first, = robowaiter("p012")
    plan(first)

    def holding(task: Task) -> Task:
        return with_init(task, [*(a for a in task.initial_state if a.predicate != "holding"),
                                Atom("holding", ("chips",))])

    held = holding(first)
    result = plan(held)
    state = held.initial_state
    for action in result.executed:
        assert action.applicable(state), action
        state = action.apply(state)
    assert all(g.holds(state) for g in held.goal_literals)
    assert "putdown" in str(result.executed[0])  # the chips first
    alone = holding(load(str(RW / "domain.pddl"), str(RW / "p012.pddl")))
    assert shape(result) == shape(plan(alone))
