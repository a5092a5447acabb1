"""External agents: whoever else changes the world between two ticks of the robot's tree.

The paper's Problem 1 is about exactly these: an agent that undoes the robot's work,
one that does the robot's work for it, one that makes an action fail, and one that
breaks an assumption (a path gets blocked). Each is an `Agent` that acts on the
world's public methods only, so any backend with those methods (the symbolic world,
scripted PyBullet scene events) can be disturbed the same way, and each reports what
it did as a `Disturbance` for the trace and the live view.
"""

from __future__ import annotations

import random
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from btplan.errors import InputError
from btplan.model import Atom, GroundAction
from btplan.worlds.disturb import DisturbSpec, Target

LeafKey = tuple[str, tuple[str, ...]]


@dataclass(frozen=True, slots=True)
class Disturbance:
    """One thing an external agent did: before which tick, who, what (in words), and its kind."""

    tick: int
    agent: str
    description: str
    kind: str


class DisturbableWorld(Protocol):
    """The public methods of a world that agents use (the symbolic world has them all)."""

    executed: list[GroundAction]
    started: list[GroundAction]

    def running_actions(self) -> list[GroundAction]:
        """The robot's actions started and not yet finished, halted or failed, oldest first.

        `help` without arguments does the last of them for the robot.
        """
        ...

    def facts(self) -> frozenset[Atom]:
        """The state now; agents compare it before and after acting to say what they changed."""
        ...

    def set_fact(self, atom: Atom) -> None:
        """Make `atom` true at once: an external change, not an action of the robot."""
        ...

    def clear_fact(self, atom: Atom) -> None:
        """Make `atom` false at once; clearing an atom that does not hold changes nothing."""
        ...

    def apply_action(self, action: GroundAction) -> None:
        """Apply `action`'s effects as if someone else did it; its preconditions are not checked."""
        ...

    def fail_next(self, action_name: str, args: tuple[str, ...] | None = None) -> None:
        """Make the next tick of a matching robot action fail; `args` None matches any arguments."""
        ...

    def ground(self, key: LeafKey) -> GroundAction:
        """The grounded action that an Action leaf's (name, arguments) key stands for."""
        ...


class Agent(Protocol):
    """Acts on the world before tick `tick`; returns what it did (nothing, most ticks).

    `world` is untyped here so that a backend's own scripted events (a PyBullet scene
    moving a cube) are agents too, whatever that backend's world offers them.
    """

    name: str

    def act(self, world: Any, tick: int) -> list[Disturbance]:
        """Change `world` before tick `tick` if this agent's time has come; [] if it did nothing."""
        ...


def running_action(world: DisturbableWorld) -> GroundAction | None:
    """The action the robot started last and has not yet finished, halted or failed."""
    running = world.running_actions()
    return running[-1] if running else None


def _matches(action: GroundAction, target: Target | None) -> bool:
    if target is None:
        return True
    return action.name == target.name and (target.args is None or action.args == target.args)


class SpecAgent:
    """An agent driven by one disturbance spec (`undo@5`, `set:blocked(t)@p=0.1`, ...).

    Its random stream is its own, seeded from the run's seed and its position, and it
    draws once on every tick its spec covers, so the same seed gives the same
    disturbances whatever else happens in the run (the benchmark relies on this).
    """

    def __init__(self, spec: DisturbSpec, seed: int = 0, index: int = 0) -> None:
        self.spec = spec
        self.name = spec.text
        self._rng = random.Random(seed * 1_000_003 + index)

    def fires(self, tick: int) -> bool:
        """Whether the spec fires at `tick`: only on ticks its timing covers, and then by one draw.

        The draw is taken on every covered tick, even at probability 1, so the stream stays
        aligned with the tick number whatever the run did before.
        """
        if not self.spec.when.covers(tick):
            return False
        draw = self._rng.random()
        return draw < self.spec.when.probability

    def act(self, world: DisturbableWorld, tick: int) -> list[Disturbance]:
        """Carry out the spec if it fires at `tick`.

        A spec with nothing to do (the fact already set, no matching action) reports nothing,
        so traces show only real changes.
        """
        if not self.fires(tick):
            return []
        done = getattr(self, "_" + self.spec.kind)(world)
        if done is None:
            return []
        return [Disturbance(tick, self.name, done, self.spec.kind)]

    def _fact(self) -> Atom:
        assert self.spec.target is not None and self.spec.target.args is not None
        return Atom(self.spec.target.name, self.spec.target.args)

    def _set(self, world: DisturbableWorld) -> str | None:
        atom = self._fact()
        if atom in world.facts():
            return None
        world.set_fact(atom)
        return f"set {atom}"

    def _clear(self, world: DisturbableWorld) -> str | None:
        atom = self._fact()
        if atom not in world.facts():
            return None
        world.clear_fact(atom)
        return f"cleared {atom}"

    def _undo(self, world: DisturbableWorld) -> str | None:
        """Reverse the effects of the robot's last executed (matching) action.

        Its added facts are cleared and its named deleted facts restored; wildcard
        deletions (`not near(_)`) cannot be restored and are left alone.
        """
        action = next((a for a in reversed(world.executed) if _matches(a, self.spec.target)), None)
        if action is None:
            return None
        state = world.facts()
        removed = sorted(a for a in action.add if a in state)
        restored = sorted(a for a in action.delete if a not in state)
        if not removed and not restored:
            return None
        for atom in removed:
            world.clear_fact(atom)
        for atom in restored:
            world.set_fact(atom)
        return f"undid {action}: " + _changes(restored, removed)

    def _help(self, world: DisturbableWorld) -> str | None:
        """Do an action for the robot: the one named with arguments, else the running one."""
        target = self.spec.target
        action: GroundAction | None
        if target is not None and target.args is not None:
            action = world.ground((target.name, target.args))
        else:
            action = running_action(world)
        if action is None or not _matches(action, target):
            return None
        before = world.facts()
        world.apply_action(action)
        after = world.facts()
        return f"did {action}: " + _changes(sorted(after - before), sorted(before - after))

    def _fail(self, world: DisturbableWorld) -> str | None:
        target = self.spec.target
        assert target is not None
        world.fail_next(target.name, target.args)
        return f"made the next {target} fail"


def _changes(added: Iterable[Atom], removed: Iterable[Atom]) -> str:
    parts = [f"+{a}" for a in added] + [f"-{a}" for a in removed]
    return " ".join(parts) if parts else "no change"


NEEDS = {
    "undo": ("executed", "facts", "set_fact", "clear_fact"),
    "help": ("running_actions", "executed", "facts", "apply_action", "ground"),
    "set": ("facts", "set_fact"),
    "clear": ("facts", "clear_fact"),
    "fail": ("fail_next",),
}
"""What a world must offer for each kind of spec agent."""


ABILITY = {
    "undo": "undo the robot's actions",
    "help": "do actions for the robot",
    "set": "set facts",
    "clear": "clear facts",
    "fail": "make actions fail",
}
"""What each kind of spec asks of the world, in the words of the domain."""


def check_world(specs: Sequence[DisturbSpec], world: Any, world_name: str) -> None:
    """Refuse specs the world cannot carry out, before the run rather than in the middle.

    A simulator changes its state through its own scene events, not by setting facts,
    so symbolic specs may not apply there. The message names the user's spec and fact,
    not the world's methods.
    """
    for spec in specs:
        if any(not hasattr(world, m) for m in NEEDS[spec.kind]):
            such = f" such as {str(spec.target).removesuffix('()')}" if spec.target else ""
            raise InputError(f"{world_name} cannot {ABILITY[spec.kind]}{such} "
                             f"(in '{spec.text}')", spec.span,
                             "change it through its scene's events instead", spec.source_line)


def agents_from_specs(specs: Sequence[DisturbSpec], seed: int = 0) -> list[Agent]:
    """One agent per spec, in the order given; that order is also the order they act in."""
    return [SpecAgent(spec, seed, index) for index, spec in enumerate(specs)]


def act_all(agents: Iterable[Agent], world: Any, tick: int) -> list[Disturbance]:
    """Let every agent act before `tick`, in order, and collect what they did."""
    done: list[Disturbance] = []
    for agent in agents:
        done.extend(agent.act(world, tick))
    return done
