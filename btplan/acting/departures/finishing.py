"""Finish a halted action first when nothing is lost (`finish_halted_action`).

btplan.acting.departures.finish has the reasons and the wrapper; this plugs it in: the
tree ticks against the wrapper, which ends its tick after the tree's.
"""

from __future__ import annotations

from btplan.acting.departures.finish import FinishFirst
from btplan.acting.hooks import Departure
from btplan.acting.state import LoopState
from btplan.bt import World


class FinishHalted(Departure):
    """The FinishFirst wrapper of the loop's world, made again for each new world."""

    name = "finish_halted_action"

    def attach(self, loop: LoopState) -> None:
        """Make the wrapper once the loop exists: it needs the loop's world and grounding."""
        super().attach(loop)
        self.wrapper = FinishFirst(loop.world, loop.grounding)

    def world_for_tick(self, world: World) -> World:
        """The `world_for_tick` hook: the tree ticks against the FinishFirst wrapper, not `world`,
        so that a halt can be held back until the tree's replacement action is known."""
        return self.wrapper

    def end_tick(self) -> None:
        """The `end_tick` hook: a carried action that nothing replaced within the tick is halted
        now, so a halt is only ever deferred inside one tick."""
        self.wrapper.end_tick()

    def new_world(self, world: World) -> None:
        """The `new_world` hook: a fresh wrapper over the loop's new world, since what the old
        one carried runs in the old world."""
        self.wrapper = FinishFirst(self.loop.world, self.loop.grounding)
