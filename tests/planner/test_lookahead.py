"""Looking ahead with the relaxed model: bindings, dead ends, and which condition to expand.

Each case is small and hand-written, and shows the failure the mechanism removes by
planning once with it and once without it (the paper's behaviour).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from btplan.acting.offline import plan
from btplan.errors import PlanningError
from btplan.lang import load
from btplan.model import Atom, Task
from btplan.planner import AchieverIndex, PlannerOptions
from tests.planner.test_classic import validate
from tests.planner.test_invariants import task_of

KITCHEN = """
(define (domain kitchen)
  (:requirements :strips :typing)
  (:types child bread sandwich)
  (:predicates (fresh ?b - bread) (plain_ok ?c - child) (free ?b - bread)
               (unmade ?s - sandwich) (ready ?s - sandwich) (safe ?s - sandwich)
               (fed ?c - child))
  (:action make_plain
    :parameters (?s - sandwich ?b - bread)
    :precondition (and (unmade ?s) (fresh ?b))
    :effect (and (not (unmade ?s)) (not (fresh ?b)) (ready ?s)))
  (:action make_safe
    :parameters (?s - sandwich ?b - bread)
    :precondition (and (unmade ?s) (fresh ?b) (free ?b))
    :effect (and (not (unmade ?s)) (not (fresh ?b)) (not (free ?b)) (ready ?s) (safe ?s)))
  (:action feed
    :parameters (?c - child ?s - sandwich)
    :precondition (and (ready ?s) (safe ?s))
    :effect (and (not (ready ?s)) (fed ?c))))
"""


def kitchen(tmp_path: Path, breads: int, eaten: int) -> Task:
    """`breads` breads of which the first `eaten` are gone; only the last one is free."""
    names = [f"b{i:03d}" for i in range(breads)]
    fresh = " ".join(f"(fresh {b})" for b in names[eaten:])
    problem = f"""(define (problem lunch) (:domain kitchen)
      (:objects kid - child s1 - sandwich {' '.join(names)} - bread)
      (:init (unmade s1) {fresh} (free {names[-1]}))
      (:goal (fed kid)))"""
    (tmp_path / "domain.pddl").write_text(KITCHEN)
    (tmp_path / "problem.pddl").write_text(problem)
    return load([str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl")])


def test_unreachable_bindings_do_not_use_up_the_binding_budget(tmp_path: Path) -> None:
    # 70 breads, 69 of them eaten: the first 64 bindings of make_safe cannot run.
    task = kitchen(tmp_path, breads=70, eaten=69)
    options = PlannerOptions(max_bindings=64)
    result = plan(task, options=options)
    validate(task, result.executed)
    with pytest.raises(PlanningError, match="no action can make"):
        plan(task, options=replace(options, prune_bindings=False, retries=0))


def test_an_achiever_that_cuts_off_a_later_condition_is_not_chosen(tmp_path: Path) -> None:
    # make_plain ranks first (fewer preconditions) but loses the only sandwich for good.
    task = kitchen(tmp_path, breads=3, eaten=0)
    options = PlannerOptions(max_alternatives=1)
    result = plan(task, options=options)
    validate(task, result.executed)
    assert [a.name for a in result.executed] == ["make_safe", "feed"]
    with pytest.raises(PlanningError):
        plan(task, options=replace(options, avoid_dead_ends=False, retries=0))


def corridor(tmp_path: Path, length: int) -> Task:
    """A robot at one end of a two-lane corridor must visit the far end."""
    cells = [f"c{lane}_{i:02d}" for lane in range(2) for i in range(length)]
    links = []
    for i in range(length):
        links.append(f"(link c0_{i:02d} c1_{i:02d}) (link c1_{i:02d} c0_{i:02d})")
        if i + 1 < length:
            for lane in range(2):
                links.append(f"(link c{lane}_{i:02d} c{lane}_{i + 1:02d})"
                             f" (link c{lane}_{i + 1:02d} c{lane}_{i:02d})")
    domain = """(define (domain walk) (:requirements :strips)
      (:predicates (at ?c) (link ?a ?b) (seen ?c))
      (:action move :parameters (?a ?b) :precondition (and (at ?a) (link ?a ?b))
        :effect (and (not (at ?a)) (at ?b) (seen ?b))))"""
    problem = f"""(define (problem far) (:domain walk) (:objects {' '.join(cells)})
      (:init (at c0_00) {' '.join(links)}) (:goal (seen c1_{length - 1:02d})))"""
    (tmp_path / "walk.pddl").write_text(domain)
    (tmp_path / "far.pddl").write_text(problem)
    return load([str(tmp_path / "walk.pddl"), str(tmp_path / "far.pddl")])


def test_the_failed_condition_nearest_the_state_is_expanded_first(tmp_path: Path) -> None:
    task = corridor(tmp_path, length=6)
    options = PlannerOptions()
    nearest = plan(task, options=options)
    validate(task, nearest.executed)
    assert nearest.stats.expansions == len(nearest.executed)  # straight to the far end
    breadth = plan(task, options=replace(options, closest_first=False))
    validate(task, breadth.executed)
    assert breadth.stats.expansions > 2 * nearest.stats.expansions


def test_producer_needs_are_the_producers_positive_preconditions() -> None:
    """The look-ahead's table of what each producer needs matches the producers, atom by
    atom, asked twice (the second answer is the one kept)."""
    for task in (task_of("blocksworld", 4), task_of("logistics", 2)):
        relaxed = AchieverIndex(task).relaxed
        atoms = {a for action in relaxed.actions for a in action.add}
        for atom in sorted(atoms):
            expected = [tuple(p.atom for p in a.preconditions if p.positive)
                        for a in relaxed.producers(atom)]
            assert relaxed.producer_needs(atom) == expected
            assert relaxed.producer_needs(atom) == expected
        assert relaxed.producer_needs(Atom("nowhere", ())) == []
