"""Goal interactions of classic planning: Sussman's anomaly and friends.

Each plan is validated independently of the planner: every executed action must be
applicable in the state where it ran, and the goal must hold at the end; and the
returned tree, ticked from the initial state with no planning, must reach the goal.
"""

from __future__ import annotations

from btplan.acting.offline import load, plan
from btplan.bt import SUCCESS
from btplan.model import GroundAction, Task
from btplan.worlds.symbolic import SymbolicWorld
from tests.planner.shapes import DOMAINS


def validate(task: Task, actions: list[GroundAction]) -> None:
    state = task.initial_state
    for action in actions:
        assert action.applicable(state), f"{action} is not applicable"
        state = action.apply(state)
    assert all(g.holds(state) for g in task.goal_literals), "the goal does not hold at the end"


def replay(task: Task, tree_plan: object, max_ticks: int = 2000) -> list[GroundAction]:
    """Tick the tree from the initial state with no planning; return what it executed."""
    world = SymbolicWorld(task)
    tree = tree_plan.tree  # type: ignore[attr-defined]
    tree.halt(world)
    for _ in range(max_ticks):
        if tree.tick(world) is SUCCESS:
            # The first SUCCESS must mean it: every goal holds after that tick.
            assert all(g.holds(world.facts()) for g in task.goal_literals)
            return world.executed
    raise AssertionError("the tree did not reach the goal from the initial state")


def test_sussman_anomaly_is_solved_by_interleaving_the_goals() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    result = plan(task)
    validate(task, result.executed)
    assert [a.ipc() for a in result.executed] == [
        "(unstack c a)", "(putdown c)", "(pickup b)", "(stack b c)", "(pickup a)", "(stack a b)"]
    assert result.stats.moves >= 1  # the goals had to be reordered
    assert [a.ipc() for a in replay(task, result)] == [a.ipc() for a in result.executed]


def test_tower_inversion_orders_the_goals_bottom_up() -> None:
    task = load(str(DOMAINS / "planner_invert.bt"))
    result = plan(task)
    validate(task, result.executed)
    assert len(result.executed) == 8  # optimal: every block moves once, a only to the table
    assert [a.ipc() for a in replay(task, result)] == [a.ipc() for a in result.executed]


def test_same_task_and_seed_give_the_same_tree_and_plan() -> None:
    from btplan.bt.formats import dump

    task = load(str(DOMAINS / "planner_invert.bt"))
    first, second = plan(task, seed=5), plan(task, seed=5)
    assert dump(first.tree, "json") == dump(second.tree, "json")
    assert [a.ipc() for a in first.executed] == [a.ipc() for a in second.executed]


def test_register_swap_saves_the_value_before_overwriting_it() -> None:
    task = load(str(DOMAINS / "planner_swap.bt"))
    result = plan(task)
    validate(task, result.executed)
    assert [a.ipc() for a in result.executed] == [
        "(copy r3 r1 a c)", "(copy r1 r2 b a)", "(copy r2 r3 a b)"]
    assert [a.ipc() for a in replay(task, result)] == [a.ipc() for a in result.executed]
