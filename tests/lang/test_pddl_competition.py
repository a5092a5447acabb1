"""PDDL as competitions write it: action costs, `either`, delete-then-add, repeated types."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.acting.offline import plan
from btplan.errors import InputError
from btplan.lang import load
from btplan.model import Atom

ROADS = """; trucks on weighted roads, IPC style
(define (domain roads)
  (:requirements :typing :action-costs)
  (:types place locatable area - object
          truck package - locatable)
  (:predicates (at ?x - (either truck package) ?p - place) (road ?a ?b - place)
               (in ?p - package ?t - truck) (moved ?t - truck))
  (:functions (total-cost) - number (road-length ?a ?b - place) - number)
  (:action drive
    :parameters (?t - truck ?a ?b - place)
    :precondition (and (at ?t ?a) (road ?a ?b))
    :effect (and (not (at ?t ?a)) (at ?t ?b) (not (moved ?t)) (moved ?t)
                 (increase (total-cost) (road-length ?a ?b))))
  (:action load
    :parameters (?p - package ?t - truck ?a - place)
    :precondition (and (at ?p ?a) (at ?t ?a))
    :effect (and (not (at ?p ?a)) (in ?p ?t) (increase (total-cost) 2)))
  (:action unload
    :parameters (?p - package ?t - truck ?a - place)
    :precondition (and (in ?p ?t) (at ?t ?a))
    :effect (and (not (in ?p ?t)) (at ?p ?a))))
"""
PROBLEM = """(define (problem deliver) (:domain roads)
  (:objects x y z - place t1 - truck p1 - package)
  (:init (at t1 x) (at p1 y) (road x y) (road y x) (road y z) (road z y)
         (= (total-cost) 0) (= (road-length x y) 5) (= (road-length y x) 5)
         (= (road-length y z) 7) (= (road-length z y) 7))
  (:goal (and (at p1 z)))
  (:metric minimize (total-cost)))
"""


def write(tmp_path: Path, domain: str = ROADS, problem: str = PROBLEM) -> list[str]:
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "p01.pddl").write_text(problem)
    return [str(tmp_path / "domain.pddl"), str(tmp_path / "p01.pddl")]


def test_action_costs_come_from_constants_and_static_functions(tmp_path: Path) -> None:
    task = load(write(tmp_path))
    assert task.domain.has_costs
    drive, load_, unload = (task.domain.action_map[n] for n in ("drive", "load", "unload"))
    assert task.instantiate(drive, ("t1", "y", "z")).cost == 7
    assert task.instantiate(load_, ("p1", "t1", "y")).cost == 2
    assert task.instantiate(unload, ("p1", "t1", "z")).cost == 0  # no increase: free
    assert task.instantiate(drive, ("t1", "x", "z")).cost == float("inf")  # no such road


def test_the_plan_cost_is_the_sum_of_the_executed_actions(tmp_path: Path) -> None:
    result = plan(load(write(tmp_path)))
    assert [str(a) for a in result.executed] == [
        "drive(t1, x, y)", "load(p1, t1, y)", "drive(t1, y, z)", "unload(p1, t1, z)"]
    assert result.stats.cost == 5 + 2 + 7 + 0


def test_an_effect_that_deletes_and_adds_an_atom_leaves_it_true(tmp_path: Path) -> None:
    task = load(write(tmp_path))
    drive = task.instantiate(task.domain.action_map["drive"], ("t1", "x", "y"))
    after = drive.apply(task.initial_state | {Atom("moved", ("t1",))})
    assert Atom("moved", ("t1",)) in after and Atom("at", ("t1", "y")) in after


def test_either_types_a_predicate_by_the_nearest_common_ancestor(tmp_path: Path) -> None:
    task = load(write(tmp_path))
    assert task.domain.predicate_map["at"].parameters[0].type == "locatable"


def test_a_type_declared_under_object_and_under_another_type_keeps_the_other(
    tmp_path: Path,
) -> None:
    domain = ROADS.replace("truck package - locatable", "truck package area - locatable")
    task = load(write(tmp_path, domain))
    assert task.domain.type_parents["area"] == "locatable"


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("(increase (total-cost) 2)", "(increase (fuel ?t) 2)",
         "only '(increase (total-cost) ...)' is supported"),
        ("(at ?t ?a) (road ?a ?b))", "(at ?t ?a) (> (road-length ?a ?b) 3))",
         "numeric comparisons ('>') are not supported"),
        ("(at ?p ?a) (at ?t ?a))", "(at ?p ?a) (when (at ?t ?a) (moved ?t)))",
         "'when' is not supported here"),
        ("?t - truck ?a - place)\n    :precondition (and (in",
         "?t - (either truck package) ?a - place)\n    :precondition (and (in",
         "'either' types are not supported here"),
    ],
)
def test_what_stays_unsupported_is_refused_where_it_is(
    tmp_path: Path, old: str, new: str, message: str
) -> None:
    assert old in ROADS
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, ROADS.replace(old, new)))
    assert message in caught.value.message
    assert caught.value.span is not None and caught.value.span.path.endswith("domain.pddl")


def test_only_minimising_total_cost_is_a_metric(tmp_path: Path) -> None:
    problem = PROBLEM.replace("minimize (total-cost)", "maximize (total-cost)")
    with pytest.raises(InputError) as caught:
        load(write(tmp_path, problem=problem))
    assert "only '(:metric minimize (total-cost))' is supported" in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 7


def test_a_cost_read_from_a_function_is_not_silently_dropped_on_export(tmp_path: Path) -> None:
    from btplan.lang.writers import bt_domain, pddl_domain

    task = load(write(tmp_path))
    for writer in (bt_domain, pddl_domain):
        with pytest.raises(InputError, match="cannot be written"):
            writer(task.domain)
