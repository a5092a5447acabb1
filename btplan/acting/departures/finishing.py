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
        super().attach(loop)
        self.wrapper = FinishFirst(loop.world, loop.grounding)

    def world_for_tick(self, world: World) -> World:
        return self.wrapper

    def end_tick(self) -> None:
        self.wrapper.end_tick()

    def new_world(self, world: World) -> None:
        self.wrapper = FinishFirst(self.loop.world, self.loop.grounding)
