"""Stub worlds and hand-built trees shared by the tree tests.

`ScriptWorld` answers actions from per-action scripts and records every call, so a test
can assert statuses and halts tick by tick. `MiniWorld` is a tiny STRIPS world with
durations, enough to replay the paper's Example 1 without the planner.
"""

from __future__ import annotations

import random
from collections import Counter
from collections.abc import Iterable

from btplan.bt import (
    FAILURE,
    RUNNING,
    SUCCESS,
    Action,
    BehaviorTree,
    Condition,
    Fallback,
    ForceFailure,
    ForceSuccess,
    Inverter,
    Node,
    Parallel,
    Retry,
    Sequence,
    Status,
    Timeout,
)
from btplan.bt.world import LeafKey


def label(key: LeafKey) -> str:
    return f"{key[0]}({','.join(key[1])})"


class ScriptWorld:
    """Conditions from a set of facts; each action returns the next status of its script.

    A script's last status repeats forever; an action without a script is RUNNING.
    `log` holds ("start"|"step"|"halt", label) in call order, `halts` counts halts.
    """

    def __init__(self, facts: Iterable[LeafKey] = (),
                 scripts: dict[str, list[Status]] | None = None) -> None:
        self.facts = set(facts)
        self.scripts = {name: list(s) for name, s in (scripts or {}).items()}
        self.log: list[tuple[str, str]] = []
        self.halts: Counter[str] = Counter()

    def check(self, key: LeafKey) -> bool:
        return key in self.facts

    def _next(self, key: LeafKey) -> Status:
        script = self.scripts.get(key[0])
        if not script:
            return RUNNING
        return script.pop(0) if len(script) > 1 else script[0]

    def start(self, key: LeafKey) -> Status:
        self.log.append(("start", label(key)))
        return self._next(key)

    def step(self, key: LeafKey) -> Status:
        self.log.append(("step", label(key)))
        return self._next(key)

    def halt(self, key: LeafKey) -> None:
        self.log.append(("halt", label(key)))
        self.halts[label(key)] += 1

    def take_log(self) -> list[tuple[str, str]]:
        out, self.log = self.log, []
        return out


class MiniWorld:
    """Facts plus actions with a duration; effects apply on completion.

    An action's `leaves` facts are deleted when it starts: the robot is no longer near
    where it was as soon as it moves, but the hand stays empty until Pick completes.
    """

    def __init__(self, facts: Iterable[LeafKey],
                 actions: dict[LeafKey, tuple[int, set[LeafKey], set[LeafKey], set[LeafKey]]]) -> None:
        self.facts = set(facts)
        self.actions = actions
        self.progress: dict[LeafKey, int] = {}
        self.log: list[tuple[str, str]] = []

    def check(self, key: LeafKey) -> bool:
        return key in self.facts

    def start(self, key: LeafKey) -> Status:
        self.log.append(("start", label(key)))
        self.progress[key] = 0
        self.facts -= self.actions[key][3]
        return self.step(key, logged=False)

    def step(self, key: LeafKey, logged: bool = True) -> Status:
        if logged:
            self.log.append(("step", label(key)))
        duration, add, delete, _ = self.actions[key]
        self.progress[key] += 1
        if self.progress[key] < duration:
            return RUNNING
        del self.progress[key]
        self.facts -= delete
        self.facts |= add
        return SUCCESS

    def halt(self, key: LeafKey) -> None:
        self.log.append(("halt", label(key)))
        self.progress.pop(key, None)


PORTS = {"on": ("o", "l"), "holding": ("o",), "near": ("l",), "free": ("t",)}


def C(pred: str, *args: str) -> Condition:
    """A condition of Example 1, with the predicate's parameter names as ports."""
    return Condition(pred, args, PORTS.get(pred, ()))


def figure7_root() -> Fallback:
    """The final tree of the paper's Example 1 (Figure 7), built by hand."""
    return Fallback([
        C("on", "cube", "goal"),
        Sequence([
            Fallback([
                C("holding", "cube"),
                Sequence([
                    Fallback([
                        C("near", "cube"),
                        Sequence([C("free", "tau_cube"),
                                  Action("MoveTo", ("cube", "tau_cube"), ("l", "t"))]),
                    ]),
                    C("hand_empty"),
                    Action("Pick", ("cube",), ("o",)),
                ]),
            ]),
            Fallback([
                C("near", "goal"),
                Sequence([C("free", "tau_goal"),
                          Action("MoveTo", ("goal", "tau_goal"), ("l", "t"))]),
            ]),
            Action("Place", ("cube", "goal"), ("o", "l")),
        ]),
    ])


def figure7_tree() -> BehaviorTree:
    return BehaviorTree(figure7_root())


NEAR = {("near", ("cube",)), ("near", ("goal",))}


def example1_world() -> MiniWorld:
    """Example 1's initial state and its three actions with the durations of pick_place.bt."""
    hand_empty = ("hand_empty", ())
    holding = ("holding", ("cube",))
    return MiniWorld(
        {hand_empty, ("free", ("tau_cube",)), ("free", ("tau_goal",))},
        {
            ("MoveTo", ("cube", "tau_cube")): (3, {("near", ("cube",))}, set(), set(NEAR)),
            ("MoveTo", ("goal", "tau_goal")): (3, {("near", ("goal",))}, set(), set(NEAR)),
            ("Pick", ("cube",)): (2, {holding}, {hand_empty}, set()),
            ("Place", ("cube", "goal")): (2, {("on", ("cube", "goal")), hand_empty}, {holding},
                                          set()),
        },
    )




def every_kind_root() -> Node:
    """A small tree with one node of every kind, for format round trips."""
    return Sequence([
        Inverter(Condition("holding", ("cube",), ("o",))),
        Fallback([Condition("hand_empty"), ForceFailure(Action("Drop", ("cube",), ("o",)))],
                 memory=True, name="drop it"),
        Parallel([Retry(Action("Pick", ("cube",), ("o",)), attempts=3),
                  Timeout(Action("Wave"), ticks=4),
                  ForceSuccess(Condition("lit", ("lamp",), ("x",), name="lamp is on"))],
                 success=2, failure=1),
        Sequence([Condition("near", ("goal",), ("l",))], memory=True),
    ], name="all kinds")


def random_root(rng: random.Random, depth: int = 3) -> Node:
    """A random tree of every node kind over conditions p/q and actions A/B."""
    if depth == 0 or rng.random() < 0.3:
        arg = rng.choice(["a", "b"])
        if rng.random() < 0.5:
            return Condition(rng.choice(["p", "q"]), (arg,), ("x",))
        return Action(rng.choice(["A", "B"]), (arg,), ("y",))
    roll = rng.random()
    if roll < 0.2:
        child = random_root(rng, depth - 1)
        decorator = rng.choice(["inverter", "success", "failure", "retry"])
        if decorator == "retry":
            return Retry(child, attempts=rng.randint(1, 3))
        return {"inverter": Inverter, "success": ForceSuccess, "failure": ForceFailure
                }[decorator](child)
    children = [random_root(rng, depth - 1) for _ in range(rng.randint(1, 3))]
    if roll < 0.3:
        return Parallel(children, success=rng.randint(1, len(children)),
                        failure=rng.randint(1, len(children)))
    kind = Sequence if roll < 0.65 else Fallback
    return kind(children, memory=rng.random() < 0.25)


__all__ = ["FAILURE", "RUNNING", "SUCCESS", "C", "MiniWorld", "ScriptWorld", "every_kind_root",
           "example1_world", "figure7_root", "figure7_tree", "label", "random_root"]
