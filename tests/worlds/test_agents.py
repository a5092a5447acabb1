"""Spec-driven agents acting on a world through its public methods only."""

from __future__ import annotations

import pytest

from btplan.errors import InputError, Span
from btplan.model import ActionTemplate, Atom, GroundAction, Literal, Parameter, instantiate
from btplan.worlds.agents import (
    SpecAgent,
    act_all,
    agents_from_specs,
    check_world,
    running_action,
)
from btplan.worlds.disturb import parse_spec

PICK = ActionTemplate(
    name="Pick", parameters=(Parameter(name="o"),),
    preconditions=(Literal(predicate="hand_empty"),),
    effects=(Literal(predicate="holding", args=("o",)),
             Literal(predicate="hand_empty", positive=False)),
)
HOLDING, EMPTY = Atom("holding", ("cube",)), Atom("hand_empty", ())


class LogWorld:
    """The smallest world with the methods agents use; it records fail requests."""

    def __init__(self, facts: set[Atom]) -> None:
        self.state = set(facts)
        self.executed: list[GroundAction] = []
        self.started: list[GroundAction] = []
        self.halted: list[GroundAction] = []
        self.failed: list[GroundAction] = []
        self.fail_requests: list[tuple[str, tuple[str, ...] | None]] = []

    def facts(self) -> frozenset[Atom]:
        return frozenset(self.state)

    def set_fact(self, atom: Atom) -> None:
        self.state.add(atom)

    def clear_fact(self, atom: Atom) -> None:
        self.state.discard(atom)

    def apply_action(self, action: GroundAction) -> None:
        self.state = set(action.apply(frozenset(self.state)))

    def fail_next(self, action_name: str, args: tuple[str, ...] | None = None) -> None:
        self.fail_requests.append((action_name, args))

    def ground(self, key: tuple[str, tuple[str, ...]]) -> GroundAction:
        return instantiate(PICK, key[1])

    def running_actions(self) -> list[GroundAction]:
        """Started and not ended, from the logs (a world may know it more directly)."""
        ended = [*self.executed, *self.halted, *self.failed]
        running = list(self.started)
        for action in ended:
            if action in running:
                running.remove(action)
        return running


def test_undo_reverses_the_last_executed_action() -> None:
    world = LogWorld({HOLDING})
    world.executed.append(instantiate(PICK, ("cube",)))
    done = SpecAgent(parse_spec("undo@3")).act(world, 3)
    assert world.facts() == {EMPTY}
    assert [(d.tick, d.kind, d.description) for d in done] == [
        (3, "undo", "undid Pick(cube): +hand_empty() -holding(cube)")]


def test_undo_does_nothing_before_its_tick_or_without_an_action() -> None:
    world = LogWorld({EMPTY})
    agent = SpecAgent(parse_spec("undo@3"))
    assert agent.act(world, 2) == [] and agent.act(world, 3) == []
    assert world.facts() == {EMPTY}


def test_help_with_arguments_applies_the_action_regardless_of_preconditions() -> None:
    world = LogWorld(set())
    done = SpecAgent(parse_spec("help:Pick(cube)@1")).act(world, 1)
    assert world.facts() == {HOLDING}
    assert done[0].description == "did Pick(cube): +holding(cube)"


def test_help_without_arguments_finishes_the_running_action() -> None:
    world = LogWorld({EMPTY})
    pick = instantiate(PICK, ("cube",))
    world.started.append(pick)
    assert running_action(world) == pick
    SpecAgent(parse_spec("help@1")).act(world, 1)
    assert world.facts() == {HOLDING}
    world.executed.append(pick)
    assert running_action(world) is None


def test_set_and_clear_report_only_real_changes() -> None:
    world = LogWorld({EMPTY})
    agents = agents_from_specs([parse_spec("set:hand_empty@1"), parse_spec("clear:hand_empty@2")])
    assert act_all(agents, world, 1) == []
    assert [d.description for d in act_all(agents, world, 2)] == ["cleared hand_empty()"]
    assert world.facts() == frozenset()


def test_fail_asks_the_world_to_fail_the_matching_action() -> None:
    world = LogWorld(set())
    SpecAgent(parse_spec("fail:Pick@1")).act(world, 1)
    SpecAgent(parse_spec("fail:Pick(cube)@1")).act(world, 1)
    assert world.fail_requests == [("Pick", None), ("Pick", ("cube",))]


def test_probabilistic_agents_repeat_with_the_same_seed() -> None:
    def firing(seed: int) -> list[int]:
        agent = SpecAgent(parse_spec("fail:Pick@p=0.3"), seed=seed)
        return [t for t in range(1, 200) if agent.fires(t)]

    assert firing(4) == firing(4)
    assert firing(4) != firing(5)
    assert 30 < len(firing(4)) < 90


def test_specs_a_world_cannot_carry_out_are_refused_up_front() -> None:
    class Rigid:
        executed = ()

        def facts(self) -> frozenset[Atom]:
            return frozenset()

    check_world([parse_spec("fail:Pick@1")], LogWorld(set()), "the log world")
    with pytest.raises(InputError) as caught:
        check_world([parse_spec("set:hand_empty@2"), parse_spec("undo@1")], Rigid(), "the rigid world")
    message = str(caught.value)
    assert "the rigid world cannot set facts such as hand_empty (in 'set:hand_empty@2')" in message
    assert "set_fact" not in message and "Rigid" not in message
    assert caught.value.span == Span("--disturb", 1, 1)
