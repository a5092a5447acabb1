"""A place for a moved subtree is refused when it can only run before what it needs.

On three generated blocks (b3 on b1, b2 on the table), the subtree for on(b1, b2)
placed at the front of the sequence that unstacks b3 from b1 runs only while
clear(b1) is false, and every way to hold b1 needs clear(b1). Likewise clear(b1)
moved before the goal on(b1, b2), not expanded yet, conflicts with what stacking needs.
"""

from __future__ import annotations

from pathlib import Path

from btplan.bt import Fallback
from btplan.bt import Sequence as SequenceNode
from btplan.lang import load
from btplan.lang.generators import generate
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import AchieverIndex
from btplan.planner.conflicts import Judge, circular_place, placement_conflicts
from btplan.planner.expand import achiever_sequence, atomic_bt, condition_node
from btplan.worlds.symbolic import SymbolicWorld


def three_blocks(tmp_path: Path) -> Task:
    domain, problem = generate("blocksworld", seed=0, blocks=3)
    assert "(on b3 b1)" in problem and "(on_table b2)" in problem
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    return load([str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl")])


def placed(task: Task, index: AchieverIndex, pursued: Atom, achiever: str) -> Fallback:
    """on(b1, b2)'s atomic BT at the front of `achiever`'s sequence for `pursued`."""
    literal = GroundLiteral(Atom("on", ("b1", "b2")), True)
    moved = atomic_bt(condition_node(literal, task), index.relaxed.producers(literal.atom), task)
    action = next(a for a in index.relaxed.producers(pursued) if str(a) == achiever)
    sequence = achiever_sequence(action, task)
    sequence.insert(0, moved)
    Fallback([condition_node(GroundLiteral(pursued, True), task), sequence])
    assert isinstance(moved.parent, SequenceNode)
    return moved


def test_a_subtree_needing_what_its_branch_pursues_is_circular(tmp_path: Path) -> None:
    task = three_blocks(tmp_path)
    index = AchieverIndex(task)
    state = SymbolicWorld(task).facts()
    judge = Judge({}, index.mutexes, relaxed=index.relaxed, state=state)
    circular = placed(task, index, Atom("clear", ("b1",)), "unstack(b3, b1)")
    assert circular_place(circular, judge)
    # Without the relaxed model (the paper's judge) no place is refused as circular.
    assert not circular_place(circular, Judge({}, index.mutexes))


def test_a_subtree_that_can_succeed_there_is_not_circular(tmp_path: Path) -> None:
    task = three_blocks(tmp_path)
    index = AchieverIndex(task)
    state = SymbolicWorld(task).facts()
    judge = Judge({}, index.mutexes, relaxed=index.relaxed, state=state)
    # Putting b3 down does not stand in the way: on(b1, b2) needs clear(b1) and clear(b2).
    free = placed(task, index, Atom("clear", ("b3",)), "put_down(b3)")
    assert not circular_place(free, judge)
    # Putting b2 down does: stacking b1 on b2 needs clear(b2) itself.
    assert circular_place(placed(task, index, Atom("clear", ("b2",)), "put_down(b2)"), judge)


def test_a_later_goal_not_expanded_yet_shows_what_its_achievers_need(tmp_path: Path) -> None:
    task = three_blocks(tmp_path)
    index = AchieverIndex(task)
    state = SymbolicWorld(task).facts()
    clear = GroundLiteral(Atom("clear", ("b1",)), True)
    moved = atomic_bt(condition_node(clear, task), index.relaxed.producers(clear.atom)[:1], task)
    goal = condition_node(GroundLiteral(Atom("on", ("b1", "b2")), True), task)
    SequenceNode([moved, goal])
    # clear(b1) excludes holding(b1), which stacking b1 on b2, its only achiever, needs.
    found = placement_conflicts(moved, Judge({}, index.mutexes, relaxed=index.relaxed,
                                             state=state))
    assert [c.condition for c in found] == ["excludes holding(b1)"]
    # The paper's judge sees only the goal itself, which clear(b1) does not exclude.
    assert placement_conflicts(moved, Judge({}, index.mutexes)) == []
