"""Watching the way ahead: conditions an outside change broke are expanded when it happens."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from btplan import run
from btplan.acting import ACTING_OPTIONS
from btplan.acting.departures.watch import broken_ahead
from btplan.acting.offline import load
from btplan.bt import RUNNING, Action, Condition, Fallback, Node, Sequence, Status
from btplan.bt.world import LeafKey
from btplan.model import Atom
from tests.presets import departures

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OBSTACLE = load(str(DOMAINS / "pick_place_obstacle.bt"))


class Facts:
    """A world of plain facts whose actions run for ever."""

    def __init__(self, *facts: str) -> None:
        self.facts = {Atom(f, ()) for f in facts}

    def check(self, key: LeafKey) -> bool:
        return Atom(key[0], ()) in self.facts

    def start(self, key: LeafKey) -> Status:
        return RUNNING

    def step(self, key: LeafKey) -> Status:
        return RUNNING

    def halt(self, key: LeafKey) -> None:
        pass

    def state(self) -> frozenset[Atom]:
        return frozenset(self.facts)


def achieve(goal: str, *alternatives: tuple[str, str]) -> Fallback:
    """Fallback(goal, Sequence(pre, action)...)."""
    return Fallback([Condition(goal), *(Sequence([Condition(pre), Action(act)])
                                       for pre, act in alternatives)])


def ticked(root: Node, world: Facts) -> frozenset[Atom]:
    """Tick once (the first action starts) and return the state of then."""
    assert root.tick(world) is RUNNING
    return world.state()


def found(root: Node, state: frozenset[Atom], before: frozenset[Atom],
          expanded: set[Node]) -> list[Node]:
    nodes, checks = broken_ahead(root, state, before, expanded)
    assert checks > 0  # it looked, and says so
    return nodes


def condition(root: Node, name: str) -> Node:
    return next(n for n in root.walk() if isinstance(n, Condition) and n.ident == name)


def test_a_condition_ahead_that_an_outside_change_broke_is_found() -> None:
    root = Sequence([achieve("a", ("p", "do_a")), achieve("b", ("q", "do_b"))])
    world = Facts("p", "q")
    before = ticked(root, world)
    world.facts.discard(Atom("q", ()))
    assert found(root, world.state(), before, set()) == [condition(root, "q")]


def test_a_condition_that_was_false_already_is_left_for_the_tick_that_reaches_it() -> None:
    root = Sequence([achieve("a", ("p", "do_a")), achieve("b", ("q", "do_b"))])
    world = Facts("p")
    before = ticked(root, world)
    world.facts.add(Atom("x", ()))  # some other change
    assert found(root, world.state(), before, set()) == []


def test_nothing_is_expanded_ahead_when_the_change_sends_the_tree_elsewhere() -> None:
    # The running action's own precondition is gone too: the next tick leaves it.
    root = Sequence([achieve("a", ("p", "do_a")), achieve("b", ("q", "do_b"))])
    world = Facts("p", "q")
    before = ticked(root, world)
    world.facts -= {Atom("p", ()), Atom("q", ())}
    assert found(root, world.state(), before, set()) == []


def test_a_broken_alternative_is_left_alone_while_another_would_run() -> None:
    root = Sequence([achieve("a", ("p", "do_a")), achieve("b", ("q", "do_b"), ("r", "do_c"))])
    world = Facts("p", "q", "r")
    before = ticked(root, world)
    world.facts.discard(Atom("q", ()))
    assert found(root, world.state(), before, set()) == []
    world.facts.discard(Atom("r", ()))  # now both alternatives fail: the first is expanded
    assert found(root, world.state(), before, set()) == [condition(root, "q")]


def test_an_expanded_condition_is_not_expanded_again() -> None:
    root = Sequence([achieve("a", ("p", "do_a")), achieve("b", ("q", "do_b"))])
    world = Facts("p", "q")
    before = ticked(root, world)
    world.facts.discard(Atom("q", ()))
    assert found(root, world.state(), before, {condition(root, "q")}) == []


def test_a_path_blocked_while_the_robot_fetches_the_cube_is_cleared_first() -> None:
    # The sphere rolls onto the path on tick 2, while the robot drives to the cube.
    # Without the watch the loop fetches the cube, finds the path blocked only when
    # about to drive through, drops the cube, clears the path and fetches it again.
    options = replace(ACTING_OPTIONS, expansions_per_tick=64)
    block = ["set:blocks(sphere, tau_goal)@2"]
    watched = run(OBSTACLE, disturb=block,
                  config=departures(options, look_ahead=True, scope_moves=True))
    lazy = run(OBSTACLE, disturb=block, config=departures(options))
    assert watched.reached and lazy.reached
    total = watched.summary()
    assert (2, "not blocks(_, tau_goal)") in [(t, e.condition) for t, e in total.expansions]
    assert total.halted == ["MoveTo(cube, tau_cube)"]
    assert "Drop(cube)" not in total.started and total.started.count("Pick(cube)") == 1
    late = lazy.summary()
    assert "Drop(cube)" in late.started and late.started.count("Pick(cube)") == 2
    assert watched.ticks < lazy.ticks
