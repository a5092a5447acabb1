"""Agents that disturb whole scenes at a rate: block a path, topple towers, move packages.

A disturbance spec changes one named fact or undoes one action; the benchmark scenarios
need agents that pick what to disturb from the current state (which tower, which
package), and that change several facts at once so that the state stays consistent.
Each draws once per tick from its own stream seeded by the run's seed, so every
executor of one seed faces the same decisions tick by tick.
"""

from __future__ import annotations

import random
from typing import Any

from btplan.model import Atom
from btplan.worlds.agents import Disturbance


class _Meddler:
    name = "meddler"

    def __init__(self, rate: float, seed: int, salt: int) -> None:
        self.rate = rate
        self.rng = random.Random(seed * 7919 + salt)

    def act(self, world: Any, tick: int) -> list[Disturbance]:
        # Two draws every tick, used or not, keep the stream aligned between executors.
        fire = self.rng.random() < self.rate
        pick = self.rng.random()
        if not fire:
            return []
        done = self.meddle(world, world.facts(), pick)
        return [] if done is None else [Disturbance(tick, self.name, done, "set")]

    def meddle(self, world: Any, state: frozenset[Atom], pick: float) -> str | None:
        raise NotImplementedError


class BlockPath(_Meddler):
    """Puts an obstacle on a free path (the paper's Example 2: the sphere on tau_goal)."""

    name = "block-path"

    def __init__(self, rate: float, seed: int, obstacle: str = "sphere",
                 path: str = "tau_goal") -> None:
        super().__init__(rate, seed, 101)
        self.obstacle = obstacle
        self.blocks = Atom("blocks", (obstacle, path))

    def meddle(self, world: Any, state: frozenset[Atom], pick: float) -> str | None:
        """Put the obstacle on the path, taking it off whatever it stood `on`.

        Nothing happens (None) while it already blocks the path or the robot holds it.
        """
        if self.blocks in state or Atom("holding", (self.obstacle,)) in state:
            return None
        for atom in sorted(state):  # it rolls away from where it was put
            if atom.predicate == "on" and atom.args[:1] == (self.obstacle,):
                world.clear_fact(atom)
        world.set_fact(self.blocks)
        return f"{self.blocks.args[0]} blocks {self.blocks.args[1]}"


class ToppleTower(_Meddler):
    """Takes the top block of a tower (not the one in the hand) and puts it on the table."""

    name = "topple"

    def __init__(self, rate: float, seed: int) -> None:
        super().__init__(rate, seed, 202)

    def meddle(self, world: Any, state: frozenset[Atom], pick: float) -> str | None:
        """Move one tower top, chosen by `pick` in [0, 1) among them in sorted order, to the table.

        None when no block stands on another. Only `on`, `on_table` and `clear` change.
        """
        tops = sorted(a for a in state if a.predicate == "on" and Atom("clear", a.args[:1]) in state)
        if not tops:
            return None
        on = tops[int(pick * len(tops))]
        block, below = on.args
        world.clear_fact(on)
        world.set_fact(Atom("on_table", (block,)))
        world.set_fact(Atom("clear", (below,)))
        return f"moved {block} from {below} to the table"


class MovePackage(_Meddler):
    """Carries a package lying somewhere to another place of the same city (logistics)."""

    name = "move-package"

    def __init__(self, rate: float, seed: int, packages: tuple[str, ...]) -> None:
        super().__init__(rate, seed, 303)
        self.packages = frozenset(packages)

    def meddle(self, world: Any, state: frozenset[Atom], pick: float) -> str | None:
        """Move one package to another place of its city, chosen by `pick` among all such moves.

        Packages in a vehicle are not `at` a place and stay put; None when nothing can move.
        """
        city = {a.args[0]: a.args[1] for a in state if a.predicate == "in_city"}
        moves = []
        for a in sorted(state):
            if a.predicate == "at" and a.args[0] in self.packages and a.args[1] in city:
                here = a.args[1]
                moves += [(a, there) for there in sorted(city)
                          if there != here and city[there] == city[here]]
        if not moves:
            return None
        at, there = moves[int(pick * len(moves))]
        world.clear_fact(at)
        world.set_fact(Atom("at", (at.args[0], there)))
        return f"moved {at.args[0]} from {at.args[1]} to {there}"
