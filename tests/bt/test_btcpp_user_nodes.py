"""A planned tree, exported, runs in BehaviorTree.CPP with leaves written as a user would.

docs/btcpp-nodes.md tells users to register one node type per ID of the exported
TreeNodesModel: conditions that read the robot's facts, and stateful actions that start,
run for a while and can be halted. These tests do that with Python leaves in BT.CPP
(behaviortreepy), over a world of their own (a dict of facts) instead of btplan's
symbolic world, and check the IDs and ports against the domain itself, so an export with
wrong IDs, kinds or ports fails here even when its TreeNodesModel agrees with its tree.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable
from pathlib import Path

import pytest

import btplan
from btplan.atoms import WILDCARD
from btplan.bt.formats.btcpp import dump_xml
from btplan.model import Literal, Task

bt = pytest.importorskip("behaviortreepy")
from btcpp_oracle import declared_models, port_free_copy, quiet_stdout

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
RUNNING_TICKS = 2
"""An action answers RUNNING on the tick that starts it and the next one; the tick after
that applies its effects and answers SUCCESS."""
MAX_TICKS = 200

Args = tuple[str, ...]


class FactWorld:
    """The robot's facts, predicate -> set of argument tuples, as a user's nodes read them.

    `_` in a condition's arguments matches any object: `blocks(_, t)` holds when some
    object blocks t. Effects come from the domain's templates, bound through the port
    names the export wrote, so wrong port names fail to bind.
    """

    def __init__(self, task: Task) -> None:
        self.task = task
        self.facts: dict[str, set[Args]] = {}
        for atom in sorted(task.initial_state):
            self.facts.setdefault(atom.predicate, set()).add(atom.args)

    def holds(self, predicate: str, args: Args) -> bool:
        if WILDCARD not in args:
            return args in self.facts.get(predicate, set())
        return any(_matches(args, fact) for fact in self.facts.get(predicate, set()))

    def apply(self, ident: str, ports: dict[str, str]) -> None:
        template = next(a for a in self.task.domain.actions if a.name == ident)
        effects = [(lit, tuple(ports.get(a, a) for a in lit.args)) for lit in template.effects]
        for lit, args in effects:  # deletes first: `not near(_), near(l)` ends at near(l)
            if not lit.positive:
                kept = {f for f in self.facts.get(lit.predicate, set()) if not _matches(args, f)}
                self.facts[lit.predicate] = kept
        for lit, args in effects:
            if lit.positive:
                self.facts.setdefault(lit.predicate, set()).add(args)

    def satisfies(self, goal: tuple[Literal, ...]) -> bool:
        return all(self.holds(g.predicate, g.args) == g.positive for g in goal)


def _matches(pattern: Args, fact: Args) -> bool:
    return len(pattern) == len(fact) and all(p in (WILDCARD, f) for p, f in zip(pattern, fact))


class UserNodes:
    """One registration per TreeNodesModel ID; instances find their ports by their name."""

    def __init__(self, xml: str, world: FactWorld) -> None:
        self.world = world
        text, self.keys = port_free_copy(xml)  # checks every leaf's ports against the model
        self.ports = {ident: ports for ident, (_, ports) in declared_models(xml).items()}
        self.started: list[tuple[str, Args]] = []
        self.halted: list[tuple[str, Args]] = []
        self.ticks_run: dict[str, int] = {}
        factory = bt.BehaviorTreeFactory()
        for ident, (kind, _) in sorted(declared_models(xml).items()):
            if kind == "Condition":
                factory.register_simple_condition(ident, self.check)
            else:
                factory.register_simple_stateful_action(
                    ident, self.on_start, self.on_running, self.on_halted)
        with quiet_stdout():
            self.tree = factory.create_tree_from_text(text)

    def check(self, node: object) -> object:
        ident, args = self.keys[node.name()]  # type: ignore[attr-defined]
        return bt.NodeStatus.SUCCESS if self.world.holds(ident, args) else bt.NodeStatus.FAILURE

    def on_start(self, node: object) -> object:
        self.started.append(self.keys[node.name()])  # type: ignore[attr-defined]
        self.ticks_run[node.name()] = 0  # type: ignore[attr-defined]
        return bt.NodeStatus.RUNNING

    def on_running(self, node: object) -> object:
        name = node.name()  # type: ignore[attr-defined]
        self.ticks_run[name] += 1
        if self.ticks_run[name] < RUNNING_TICKS:
            return bt.NodeStatus.RUNNING
        ident, args = self.keys[name]
        self.world.apply(ident, dict(zip(self.ports[ident], args, strict=True)))
        return bt.NodeStatus.SUCCESS

    def on_halted(self, node: object) -> None:
        self.halted.append(self.keys[node.name()])  # type: ignore[attr-defined]

    def tick(self) -> str:
        with quiet_stdout():
            return str(self.tree.tick_exactly_once().name)


def _exported(name: str) -> tuple[Task, btplan.PlanResult, str]:
    task = btplan.load(str(DOMAINS / f"{name}.bt"))
    result = btplan.plan(task)
    return task, result, dump_xml(result.tree)


def _check_model_against_domain(task: Task, xml: str) -> None:
    """Actions are the domain's templates and conditions its predicates, ports their
    parameter names in order, and every declared ID is used in the tree."""
    signatures = {a.name: ("Action", [p.name for p in a.parameters]) for a in task.domain.actions}
    signatures.update({p.name: ("Condition", [q.name for q in p.parameters])
                       for p in task.domain.predicates})
    models = declared_models(xml)
    for ident, (kind, ports) in sorted(models.items()):
        assert (ident, signatures.get(ident)) == (ident, (kind, ports))
    _, keys = port_free_copy(xml)
    assert sorted({ident for ident, _ in keys.values()}) == sorted(models)


@pytest.mark.parametrize("name", ["pick_place", "pick_place_obstacle"])
def test_user_leaves_run_the_exported_tree_to_the_goal(name: str) -> None:
    task, result, xml = _exported(name)
    _check_model_against_domain(task, xml)
    world = FactWorld(task)
    nodes = UserNodes(xml, world)
    statuses: list[str] = []
    while len(statuses) < MAX_TICKS and "SUCCESS" not in statuses:
        statuses.append(nodes.tick())
    assert statuses[-1] == "SUCCESS", statuses[-5:]
    done = len(statuses) - 1
    assert set(statuses[:done]) == {"RUNNING"}
    assert world.satisfies(task.problem.goal)
    assert nodes.started == [(a.name, a.args) for a in result.executed]
    assert nodes.halted == []
    # Each action succeeds RUNNING_TICKS ticks after its start, and the tree starts the
    # next one in that same tick: conditions cost no ticks.
    assert done == len(result.executed) * RUNNING_TICKS


def _tick_while_running(nodes: UserNodes, disturb: Callable[[], None]) -> str:
    """Tick until the tree stops running (at most MAX_TICKS), disturbing after each tick."""
    status = "RUNNING"
    for _ in range(MAX_TICKS):
        status = nodes.tick()
        if status != "RUNNING":
            break
        disturb()
    return status


def test_a_higher_priority_branch_halts_the_running_action() -> None:
    """The cube slips while the robot drives to the goal: Pick takes over and the
    ReactiveSequence halts MoveTo(goal), which starts again once the cube is held."""
    task, result, xml = _exported("pick_place")
    world = FactWorld(task)
    nodes = UserNodes(xml, world)
    moving = ("MoveTo", ("goal", "tau_goal"))

    def slip() -> None:
        if nodes.started[-1] == moving and moving not in nodes.halted:
            world.facts["holding"].discard(("cube",))
            world.facts.setdefault("hand_empty", set()).add(())

    status = _tick_while_running(nodes, slip)
    assert status == "SUCCESS"
    assert world.satisfies(task.problem.goal)
    assert nodes.halted == [moving]
    plan = [(a.name, a.args) for a in result.executed]
    assert plan == [("MoveTo", ("cube", "tau_cube")), ("Pick", ("cube",)), moving,
                    ("Place", ("cube", "goal"))]
    assert nodes.started == plan[:3] + [("Pick", ("cube",)), moving, plan[3]]


def test_the_exported_tree_does_not_grow_when_the_path_is_blocked() -> None:
    """Example 2 in BT.CPP: the sphere rolls onto the path while the robot carries the
    cube. The exported tree has no branch for `blocks(sphere, tau_goal)`, so it halts
    MoveTo(goal) and fails; growing the tree at run time is btplan's loop's job."""
    task, _, xml = _exported("pick_place_obstacle")
    guards = [(i.tag, [(c.tag, c.attrib) for c in i])
              for i in ET.fromstring(xml).iter("Inverter")]
    assert ("Inverter", [("blocks", {"o": WILDCARD, "t": "tau_goal"})]) in guards
    world = FactWorld(task)
    nodes = UserNodes(xml, world)
    moving = ("MoveTo", ("goal", "tau_goal"))

    def roll() -> None:
        if nodes.started[-1] == moving:
            world.facts.setdefault("blocks", set()).add(("sphere", "tau_goal"))

    status = _tick_while_running(nodes, roll)
    assert status == "FAILURE"
    assert nodes.halted == [moving]
    assert not world.satisfies(task.problem.goal)
