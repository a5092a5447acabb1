"""Mutex groups from lifted invariants: found on templates, sound against h^2."""

from __future__ import annotations

import itertools

from btplan.lang.generators import GENERATORS
from btplan.model import ActionTemplate, Atom, Domain, GroundLiteral, Literal, Predicate, Task
from btplan.model import Parameter as P
from btplan.planner import AchieverIndex, Mutexes
from btplan.classical.invariants import MutexGroups


def task_of(name: str, size: int) -> Task:
    domain, problem = GENERATORS[name](size, seed=1)
    return Task(domain=domain, problem=problem)


def groups(task: Task) -> list[list[tuple[str, tuple[int, ...]]]]:
    return sorted(sorted(c) for c in MutexGroups(task.domain, task.initial_state).candidates)


def test_blocksworld_has_its_three_textbook_invariants() -> None:
    assert groups(task_of("blocksworld", 5)) == [
        [("clear", (0,)), ("holding", (0,)), ("on", (1,))],
        [("hand_empty", ()), ("holding", ())],
        [("holding", (0,)), ("on", (0,)), ("on_table", (0,))],
    ]


def test_two_atoms_of_one_instance_exclude_each_other_and_others_do_not() -> None:
    task = task_of("blocksworld", 5)
    found = MutexGroups(task.domain, task.initial_state)
    assert found.exclusive(Atom("on", ("b1", "b2")), Atom("holding", ("b1",)))
    assert found.exclusive(Atom("on", ("b1", "b2")), Atom("on", ("b3", "b2")))
    assert not found.exclusive(Atom("on", ("b1", "b2")), Atom("on", ("b2", "b3")))
    assert not found.exclusive(Atom("on", ("b1", "b2")), Atom("on", ("b1", "b2")))


def test_an_effect_that_deletes_and_adds_one_atom_balances_nothing() -> None:
    # add(x) deletes token() and adds it again: token stays, so item(x) joins it.
    add = ActionTemplate(
        name="add", parameters=(P(name="x"),),
        preconditions=(Literal(predicate="token"),),
        effects=(Literal(predicate="token", positive=False), Literal(predicate="token"),
                 Literal(predicate="item", args=("x",))))
    domain = Domain(name="d", predicates=(Predicate(name="token"),
                                          Predicate(name="item", parameters=(P(name="x"),))),
                    actions=(add,))
    found = MutexGroups(domain, [Atom("token", ())])
    assert not found.exclusive(Atom("token", ()), Atom("item", ("a",)))


def test_invariant_mutexes_are_h2_mutexes_on_reachable_atoms() -> None:
    for name, size in (("blocksworld", 6), ("gripper", 3), ("logistics", 2)):
        task = task_of(name, size)
        actions = AchieverIndex(task).relaxed.actions
        h2 = Mutexes(actions, task.initial_state)
        lifted = Mutexes(actions, task.initial_state, task.domain, h2_max_atoms=0)
        assert lifted.groups is not None and h2.groups is None
        reached = [a for a in h2._index if h2._reached >> h2._index[a] & 1]
        pairs = [(GroundLiteral(a), GroundLiteral(b)) for a, b in itertools.combinations(reached, 2)]
        claimed = [(a, b) for a, b in pairs if lifted.exclusive(a, b)]
        assert claimed, name
        assert all(h2.exclusive(a, b) for a, b in claimed), name
