"""PDDL import: the supported fragment reads into the same models; the rest is refused by name."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.errors import InputError
from btplan.lang import collect, load
from btplan.model import Literal

DOMAIN = """; a typed blocksworld with constants, equality and negative preconditions
(define (domain BLOCKS)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types block - object table)
  (:constants the-table - table)
  (:predicates (on ?x - block ?y - block) (ontable ?x - block) (clear ?x - block)
               (handempty) (holding ?x - block) (painted ?x))
  (:action PICK-UP
     :parameters (?x - block)
     :precondition (and (clear ?x) (ontable ?x) (handempty) (not (painted ?x)))
     :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x)))
  (:action stack
     :parameters (?x ?y - block)
     :precondition (and (holding ?x) (clear ?y) (not (= ?x ?y)))
     :effect (and (not (holding ?x)) (not (clear ?y)) (clear ?x) (handempty) (on ?x ?y))))
"""
PROBLEM = """(define (problem two) (:domain blocks)
  (:objects a b - block)
  (:init (clear a) (clear b) (ontable a) (ontable b) (handempty))
  (:goal (and (on a b) (not (holding b)))))
"""


def write(tmp_path: Path, domain: str = DOMAIN, problem: str = PROBLEM) -> list[str]:
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    return [str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]


def test_the_supported_fragment_reads_into_models(tmp_path: Path) -> None:
    task = load(write(tmp_path))
    domain = task.domain
    assert domain.name == "blocks"  # PDDL is case-insensitive: names are lowered
    assert domain.requirements == (":strips", ":typing", ":negative-preconditions", ":equality")
    assert [a.name for a in domain.actions] == ["pick-up", "stack"]
    stack = domain.action_map["stack"]
    assert [(p.name, p.type) for p in stack.parameters] == [("x", "block"), ("y", "block")]
    assert stack.constraints == (Literal(predicate="=", args=("x", "y"), positive=False),)
    assert "not painted(x)" in [str(p) for p in domain.action_map["pick-up"].preconditions]
    assert domain.predicate_map["painted"].parameters[0].type == "object"
    assert [c.name for c in domain.constants] == ["the-table"]
    assert [str(g) for g in task.goal_literals] == ["on(a, b)", "not holding(b)"]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("(:requirements :strips :adl)", "requirement ':adl' is not supported"),
        ("(:requirements :conditional-effects)", "requirement ':conditional-effects'"),
        ("(:requirements :numeric-fluents)", "requirement ':numeric-fluents' is not supported"),
        ("(:types a - (either b c))", "'either' types are not supported here"),
    ],
)
def test_unsupported_requirements_are_refused_by_name(
    tmp_path: Path, text: str, message: str
) -> None:
    domain = DOMAIN.replace(
        "(:requirements :strips :typing :negative-preconditions :equality)", text
    )
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, domain))
    assert message in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 3


@pytest.mark.parametrize(
    ("construct", "requirement"),
    [
        ("(or (clear ?x) (handempty))", ":disjunctive-preconditions"),
        ("(forall (?z - block) (clear ?z))", ":universal-preconditions"),
        ("(exists (?z - block) (clear ?z))", ":existential-preconditions"),
        ("(when (clear ?x) (handempty))", ":conditional-effects"),
    ],
)
def test_constructs_outside_the_fragment_name_their_requirement(
    tmp_path: Path, construct: str, requirement: str
) -> None:
    domain = DOMAIN.replace("(not (painted ?x))", construct)
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, domain))
    assert requirement in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 10


def test_pddl_errors_are_located(tmp_path: Path) -> None:
    problem = PROBLEM.replace("(clear b)", "(clear c)")
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, problem=problem))
    error = caught.value
    assert error.message == "unknown object 'c' in an initial fact"
    assert error.span is not None and (error.span.line, error.span.column) == (3, 27)
    assert error.source_line is not None and error.source_line[error.span.column - 1] == "c"


def test_unbalanced_parentheses_point_at_the_end(tmp_path: Path) -> None:
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, problem=PROBLEM.rstrip().rstrip(")")))
    assert "the file ends too early" in caught.value.message or "unexpected" in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 4


def test_a_variable_that_shadows_a_constant_is_renamed(tmp_path: Path) -> None:
    domain = DOMAIN.replace("?y", "?the-table")
    stack = collect(write(tmp_path, domain)).domains[0].action_map["stack"]
    assert [p.name for p in stack.parameters] == ["x", "the-table_"]
    assert "on(x, the-table_)" in [str(e) for e in stack.effects]


def test_an_unknown_variable_keeps_its_question_mark(tmp_path: Path) -> None:
    domain = DOMAIN.replace("(on ?x ?y))))", "(on ?x ?z))))")
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, domain))
    assert caught.value.message == "unbound variable '?z' in a postcondition of stack"


UNTYPED = """;;; the classic untyped 4-operator blocksworld, upper case as often found
(define (domain BLOCKS)
  (:requirements :strips)
  (:predicates (on ?x ?y) (ontable ?x) (clear ?x) (handempty) (holding ?x))
  (:action pick-up
     :parameters (?x)
     :precondition (and (clear ?x) (ontable ?x) (handempty))
     :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x))))
(define (problem BLOCKS-4-0) (:domain BLOCKS) (:objects D B A C)
  (:INIT (CLEAR C) (CLEAR A) (ONTABLE C) (ONTABLE A) (HANDEMPTY))
  (:goal (AND (ON D C) (ON C B))))
"""


def test_untyped_domain_and_problem_in_one_file(tmp_path: Path) -> None:
    (tmp_path / "both.pddl").write_text(UNTYPED)
    task = load([str(tmp_path / "both.pddl")])
    assert task.problem.name == "blocks-4-0"
    assert task.objects_of("object") == ("a", "b", "c", "d")
    assert [str(g) for g in task.goal_literals] == ["on(d, c)", "on(c, b)"]


def test_parent_types_named_only_after_a_dash_are_declared(tmp_path: Path) -> None:
    (tmp_path / "d.pddl").write_text(
        "(define (domain t) (:requirements :typing)"
        " (:types truck car - vehicle) (:predicates (at ?v - vehicle)))"
    )
    domain = collect([str(tmp_path / "d.pddl")]).domains[0]
    assert domain.type_parents == {
        "object": None,
        "truck": "vehicle",
        "car": "vehicle",
        "vehicle": "object",
    }


def test_a_domain_defined_twice_in_one_file_is_refused_at_the_second(tmp_path: Path) -> None:
    path = tmp_path / "twice.pddl"
    path.write_text(DOMAIN + "\n" + DOMAIN)
    with pytest.raises(InputError) as caught:
        collect([str(path)])
    assert "domain 'blocks' is defined twice in this file" in str(caught.value)
    assert caught.value.span is not None and caught.value.span.line > DOMAIN.count("\n")


def test_a_domain_without_a_problem_gets_a_pddl_hint(tmp_path: Path) -> None:
    path = tmp_path / "domain.pddl"
    path.write_text(DOMAIN)
    with pytest.raises(InputError) as caught:
        load([str(path)])
    assert "no problem found" in str(caught.value)
    assert "(define (problem NAME)" in (caught.value.hint or "")


def test_a_file_with_carriage_returns_only_reads_as_with_newlines(tmp_path: Path) -> None:
    plain, old_mac = tmp_path / "d.pddl", tmp_path / "cr.pddl"
    plain.write_text(DOMAIN)
    old_mac.write_text(DOMAIN.replace("\n", "\r"))
    problem = tmp_path / "p.pddl"
    problem.write_text(PROBLEM)
    assert load([str(old_mac), str(problem)]) == load([str(plain), str(problem)])
