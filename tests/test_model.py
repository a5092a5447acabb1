"""The shared models: grounding, state updates with wildcards, type hierarchy."""

from __future__ import annotations

from dataclasses import FrozenInstanceError
from pathlib import Path

import pytest

from btplan.model import (
    ActionTemplate,
    Atom,
    Domain,
    GroundLiteral,
    Literal,
    Parameter,
    Problem,
    Task,
    TypeDef,
    TypedName,
    instantiate,
)

MOVE = ActionTemplate(
    name="MoveTo",
    parameters=(Parameter(name="l", type="location"), Parameter(name="t", type="trajectory", refined=True)),
    constraints=(Literal(predicate="route", args=("l", "t")),),
    preconditions=(Literal(predicate="free", args=("t",)), Literal(predicate="=", args=("l", "l"))),
    effects=(Literal(predicate="near", args=("_",), positive=False), Literal(predicate="near", args=("l",))),
    duration=3,
)


def test_instantiate_binds_parameters_and_keeps_constraints_out() -> None:
    ground = instantiate(MOVE, ("goal", "tau_goal"))
    assert ground.preconditions == (GroundLiteral(Atom("free", ("tau_goal",)), True),)
    assert ground.add == (Atom("near", ("goal",)),)
    assert ground.delete_patterns == (Atom("near", ("_",)),)
    assert ground.port_names == ("l", "t") and ground.duration == 3
    assert ground.ipc() == "(moveto goal tau_goal)"


def test_wildcard_delete_clears_every_match_then_adds() -> None:
    ground = instantiate(MOVE, ("goal", "tau_goal"))
    state = frozenset({Atom("near", ("cube",)), Atom("near", ("goal",)), Atom("free", ("tau_goal",))})
    after = ground.apply(state)
    assert after == frozenset({Atom("near", ("goal",)), Atom("free", ("tau_goal",))})
    assert ground.deletes(Atom("near", ("cube",)))
    assert not ground.deletes(Atom("near", ("goal",)))  # added back by the same action


def test_wrong_arity_is_refused() -> None:
    with pytest.raises(ValueError):
        instantiate(MOVE, ("goal",))


def test_atoms_hash_like_leaf_keys() -> None:
    assert Atom("holding", ("cube",)) in {("holding", ("cube",))}


def test_types_and_objects() -> None:
    domain = Domain(
        name="d",
        types=(TypeDef(name="object", parent=None), TypeDef(name="location"),
               TypeDef(name="thing", parent="location"), TypeDef(name="cube", parent="thing")),
        constants=(TypedName(name="goal", type="location"),),
    )
    task = Task(domain=domain, problem=Problem(
        name="p", domain="d", objects=(TypedName(name="c1", type="cube"), TypedName(name="t", type="thing")),
        init=(Literal(predicate="hand_empty"),), goal=(Literal(predicate="on", args=("c1", "goal")),)))
    assert domain.ancestors("cube") == ("cube", "thing", "location", "object")
    assert task.objects_of("thing") == ("c1", "t")
    assert task.objects_of("location") == ("c1", "goal", "t")
    assert task.initial_state == frozenset({Atom("hand_empty", ())})
    assert task.goal_literals == (GroundLiteral(Atom("on", ("c1", "goal"))),)


def test_models_are_frozen_and_strict() -> None:
    with pytest.raises(FrozenInstanceError):
        MOVE.name = "Other"  # type: ignore[misc]
    with pytest.raises(TypeError):
        Literal(predicate="p", colour="red")  # type: ignore[call-arg]


def test_predicate_ports_are_the_predicates_parameter_names() -> None:
    from btplan.lang import load as load_task

    root = Path(__file__).resolve().parents[1]
    domain = load_task([str(root / "domains" / "pick_place_obstacle.bt")]).domain
    assert domain.predicate_ports == {p.name: tuple(q.name for q in p.parameters)
                                      for p in domain.predicates}
    assert domain.predicate_ports  # not empty
