"""h^2 mutexes: the fast fixpoint (bit rows, delete patterns by predicate) against a
plain one over sets of pairs, written from the definition."""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from pathlib import Path

from btplan.acting import load
from btplan.model import Atom, GroundAction, GroundLiteral, Task
from btplan.planner import AchieverIndex, Mutexes
from tests.planner.test_invariants import task_of

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
RW = Path(__file__).resolve().parents[2] / "bench" / "problems" / "btpg_rw_single"


def plain_h2(actions: Sequence[GroundAction], initial: Iterable[Atom],
             atoms: Sequence[Atom]) -> set[frozenset[Atom]]:
    """Reachable pairs ({a} for a reachable atom a): an action whose preconditions hold
    pairwise reaches each added atom with each other added atom, and with every atom it
    does not delete that holds with all of its preconditions."""
    init = set(initial)
    pairs = {frozenset((a, b)) for a in init for b in init}
    changed = True
    while changed:
        changed = False
        for action in actions:
            pre = [p.atom for p in action.preconditions if p.positive]
            if any(frozenset((a, b)) not in pairs for a in pre for b in pre):
                continue
            kept = [r for r in atoms if frozenset((r, r)) in pairs
                    and (r in action.add or not action.deletes(r))
                    and all(frozenset((r, p)) in pairs for p in pre)]
            for q in action.add:
                for r in [*action.add, *kept]:
                    if frozenset((q, r)) not in pairs:
                        pairs.add(frozenset((q, r)))
                        changed = True
    return pairs


def _tasks() -> list[Task]:
    return [load(str(DOMAINS / "pick_place_obstacle.bt")), task_of("blocksworld", 4),
            task_of("gripper", 2), task_of("logistics", 2)]


def test_the_fixpoint_finds_the_pairs_of_the_definition() -> None:
    tasks = _tasks()
    obstacle = AchieverIndex(tasks[0]).relaxed.actions
    assert any(a.delete_patterns for a in obstacle)  # `not near(_)`: patterns are covered
    for task in tasks:
        actions = AchieverIndex(task).relaxed.actions
        found = Mutexes(actions, task.initial_state)
        atoms = sorted({*task.initial_state,
                        *(p.atom for a in actions for p in a.preconditions),
                        *(x for a in actions for x in (*a.add, *a.delete))})
        pairs = plain_h2(actions, task.initial_state, atoms)
        for a in atoms:
            assert found.unreachable(a) is (frozenset((a, a)) not in pairs), a
        for a, b in itertools.combinations(atoms, 2):
            both = frozenset((a, a)) in pairs and frozenset((b, b)) in pairs
            exclusive = found.exclusive(GroundLiteral(a, True), GroundLiteral(b, True))
            assert exclusive is (both and frozenset((a, b)) not in pairs), (a, b)


def _pairwise(mutexes: Mutexes, atoms: Sequence[Atom]) -> bool:
    known = [GroundLiteral(a) for a in atoms if mutexes.knows(a)]
    return any(mutexes.exclusive(a, b) for i, a in enumerate(known) for b in known[i + 1:])


def test_all_pairs_at_once_agree_with_one_pair_at_a_time() -> None:
    """`any_exclusive` (bit rows, or invariant groups for large tasks) says what asking
    `exclusive` of every pair says: for every achiever's preconditions, and for every
    set of up to three atoms, repeats and unknown atoms included."""
    unknown = Atom("nowhere", ("x",))
    for task in _tasks():
        actions = AchieverIndex(task).relaxed.actions
        for mutexes in (Mutexes(actions, task.initial_state),
                        Mutexes(actions, task.initial_state, task.domain, h2_max_atoms=0)):
            atoms = sorted({p.atom for a in actions for p in a.preconditions})
            sets = [[p.atom for p in a.preconditions if p.positive] for a in actions]
            sets += [list(c) for c in itertools.combinations(atoms[:12], 2)]
            sets += [list(c) for c in itertools.combinations(atoms[:10], 3)]
            sets += [[a, a] for a in atoms[:5]] + [[unknown, a] for a in atoms[:5]]
            verdicts = [mutexes.any_exclusive(s) for s in sets]
            assert verdicts == [_pairwise(mutexes, s) for s in sets]
            assert any(verdicts) and not all(verdicts)


def _screened(mutexes: Mutexes, needs: list[GroundLiteral], held: tuple[GroundLiteral, ...]
              ) -> tuple[bool, list[GroundLiteral]]:
    unknown: list[GroundLiteral] = []
    for need in needs:
        if not mutexes.knows(need.atom):
            unknown.append(need)
        elif any(mutexes.exclusive(h, need) for h in held):
            return True, unknown
    return False, unknown


def test_needs_against_many_held_agree_with_one_pair_at_a_time() -> None:
    """`screen(needs, held)` says what asking `knows` of each need and `exclusive(hold,
    need)` of each held literal says, in order: both signs, the same atom negated,
    unreached and unknown atoms."""
    unknown = Atom("nowhere", ("x",))
    for task in _tasks():
        actions = AchieverIndex(task).relaxed.actions
        for mutexes in (Mutexes(actions, task.initial_state),
                        Mutexes(actions, task.initial_state, task.domain, h2_max_atoms=0)):
            atoms = sorted({p.atom for a in actions for p in a.preconditions})[:14] + [unknown]
            literals = [GroundLiteral(a, s) for a in atoms for s in (True, False)]
            needs = [[n] for n in literals] + [list(c) for c in itertools.combinations(
                literals[::3], 2)] + [[GroundLiteral(unknown), *literals[:4:2]]]
            verdicts = []
            for need in needs:
                for held in itertools.combinations(literals, 2):
                    verdict = mutexes.screen(need, held)
                    assert verdict == _screened(mutexes, need, held), (need, held)
                    verdicts.append(verdict[0])
            assert any(verdicts) and not all(verdicts)


def test_mutexes_computed_when_asked_answer_as_those_computed_at_once() -> None:
    """Mutexes given their actions as a function answer some questions without the
    fixpoint (fewer than two atoms; atoms that all hold initially, or all one action
    away; what h^2 knows of); every answer, asked of one not yet computed, is the answer
    of mutexes computed at once (h^2, and invariant groups), and questions that need
    more make them be computed."""
    robowaiter = load(str(RW / "domain.pddl"), str(RW / "p004.pddl"))
    verdicts: list[bool] = []
    for task in [*_tasks(), robowaiter]:
        actions = AchieverIndex(task).relaxed.actions
        initial = sorted(task.initial_state)
        ahead = sorted({a for action in actions if action.applicable(task.initial_state)
                        for a in action.add} - task.initial_state)
        atoms = initial[:4] + ahead[:4] + sorted({p.atom for a in actions
                                                  for p in a.preconditions})[:4]
        literals = [GroundLiteral(a, sign) for a in atoms[::2] for sign in (True, False)]
        for limit in (2000, 0):
            eager = Mutexes(actions, task.initial_state, task.domain, h2_max_atoms=limit)
            lazy: list[Mutexes] = []

            def fresh() -> Mutexes:
                """Not yet computed: a new one once a question made the last one compute."""
                if not lazy or lazy[-1].computed:
                    lazy.append(Mutexes(lambda: actions, task.initial_state, task.domain,
                                        h2_max_atoms=limit))
                return lazy[-1]

            assert not fresh().any_exclusive(initial) and not fresh().any_exclusive(atoms[-1:])
            assert not lazy[-1].computed and fresh().ready().computed
            # invariant groups answer pairs of the initial state only, and are slow to make
            for a, b in itertools.product(atoms if limit else initial[:4] + atoms[-2:], repeat=2):
                first, second = GroundLiteral(a), GroundLiteral(b)
                verdicts.append(eager.exclusive(first, second))
                assert fresh().exclusive(first, second) is verdicts[-1]
                assert fresh().any_exclusive([a, b]) is eager.any_exclusive([a, b])
            if limit == 0:
                continue  # invariant groups: asked anything else, they are computed
            for atom in atoms:
                assert fresh().knows(atom) is eager.knows(atom)
            for need in list(itertools.combinations(literals, 2))[::5]:
                for held in itertools.combinations(literals[:6], 2):
                    assert fresh().screen(need, held) == eager.screen(need, held), (need, held)
    assert any(verdicts) and not all(verdicts)


def test_questions_answered_without_the_fixpoint_do_not_compute_it() -> None:
    """Pairs of the initial state, pairs one action away from it (the robot moved next
    to the yogurt, the hand still empty) and the atoms h^2 knows of are answered from
    the actions alone; a pair further away (the yogurt held next to the bar) is not."""
    task = load(str(RW / "domain.pddl"), str(RW / "p004.pddl"))
    actions = AchieverIndex(task).relaxed.actions
    near, empty = Atom("robotnear", ("yogurt",)), Atom("holding", ("nothing",))
    held, bar = Atom("holding", ("yogurt",)), Atom("robotnear", ("bar",))
    mutexes = Mutexes(lambda: actions, task.initial_state, task.domain)
    assert not mutexes.any_exclusive([near, empty]) and not mutexes.any_exclusive(
        sorted(task.initial_state))
    assert not mutexes.exclusive(GroundLiteral(near), GroundLiteral(empty))
    assert mutexes.screen([GroundLiteral(near)], [GroundLiteral(empty)]) == (False, [])
    assert mutexes.knows(near) and not mutexes.computed
    assert not mutexes.exclusive(GroundLiteral(held), GroundLiteral(bar))
    assert mutexes.computed
    fresh = Mutexes(lambda: actions, task.initial_state, task.domain)
    assert fresh.exclusive(GroundLiteral(near), GroundLiteral(bar))  # one place at a time
    assert fresh.computed
