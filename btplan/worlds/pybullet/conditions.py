"""The domain's conditions, measured on the scene every time they are asked.

Nothing is read from a stored symbolic state, so a change made by an external agent is
seen on the next tick. `blocks(c, t)` re-plans a stale trajectory before checking it;
only a cube blocks a trajectory, in `check` as in `facts`: the planner looks achievers
up in the facts, so a condition false for another reason would have none.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TypeVar

from btplan.errors import WorldError
from btplan.model import Atom
from btplan.worlds.pybullet.routes import Routes

Key = tuple[str, tuple[str, ...]]
T = TypeVar("T")


class Conditions:
    """`check` for one condition, `facts` for the whole state (the planner's view)."""

    def __init__(self, routes: Routes, assumed: frozenset[Atom]) -> None:
        self.routes, self.state = routes, routes.state
        self.assumed = assumed
        self.seconds = 0.0
        """Wall time spent measuring conditions and facts, without the base's OMPL solves
        they caused (bench/sim.py reports those apart)."""

    def check(self, key: Key) -> bool:
        """Measure one condition on the scene now, with no stored state, timed into `seconds`.

        A predicate the world has no measure for raises WorldError.
        """
        return self._timed(lambda: self._check(key))

    def _check(self, key: Key) -> bool:
        state = self.state
        name, args = key
        if name == "near":
            return state.is_near(args[0])
        if name == "holding":
            return state.in_hand(args[0]) is not None
        if name == "hand_empty":
            return state.in_hand() is None
        if name == "on":
            return state.on(args[0], args[1])
        if name == "blocks":
            # Only cubes block, as in `facts`: a trajectory without a path ("(no path)")
            # has nothing to put aside, and the move itself fails with why.
            found = self.routes.blockers(args[1]) & state.sim.cubes.keys()
            return bool(found) if args[0] == "_" else args[0] in found
        if name == "route":
            traj = state.trajectories.get(args[1])
            return traj is not None and traj.target == args[0]
        raise WorldError(f"the PyBullet world cannot evaluate the condition {name!r}")

    def facts(self) -> frozenset[Atom]:
        """Every condition of the domain's vocabulary that holds now, as atoms."""
        return self._timed(self._known_facts)

    def _known_facts(self) -> frozenset[Atom]:
        """The facts, measured once between two changes: the loop asks at the end of one
        tick and at the start of the next, and the scene's agents mostly did nothing between."""
        memo = self.state.sim.memo  # forgotten at every physics step and every teleport
        known = memo.get("facts")
        if isinstance(known, tuple) and known[0] == self._mark():
            return known[1]  # type: ignore[no-any-return]
        found = self._facts()
        memo["facts"] = (self._mark(), found)
        return found

    def _mark(self) -> tuple[object, ...]:
        """What the facts depend on besides the simulation: the world's own bookkeeping."""
        state = self.state
        return (state.bookkeeping(), tuple(sorted(self.routes.last_blockers.items())))

    def _timed(self, measure: Callable[[], T]) -> T:
        """Run `measure`, adding its wall time, less the base's OMPL solves, to `seconds`."""
        solves, began = len(self.routes.plan_seconds), time.perf_counter()
        try:
            return measure()
        finally:
            self.seconds += time.perf_counter() - began - sum(self.routes.plan_seconds[solves:])

    def _facts(self) -> frozenset[Atom]:
        state = self.state
        found: set[Atom] = set(self.assumed)
        locations = [*state.cube_names, *(r.name for r in state.scene.regions), *sorted(state.poses)]
        found.update(Atom("near", (n,)) for n in locations if state.is_near(n))
        held = state.in_hand()
        found.add(Atom("hand_empty", ()) if held is None else Atom("holding", (held,)))
        places = [*(r.name for r in state.scene.regions), *sorted(state.poses)]  # where `on` can hold
        found.update(Atom("on", (c, p)) for c in state.cube_names if state.resting(c)
                     for p in places if state.on(c, p))
        for name in sorted(state.trajectories):
            traj = state.trajectories[name]
            found.add(Atom("route", (traj.target, name)))
            if traj.stale(state.base, traj.goal, state.layout()) or not state.present(traj.target):
                blocking = self.routes.last_blockers.get(name, frozenset())  # check() measures it
            else:
                blocking = self.routes.blockers(name)
            found.update(Atom("blocks", (c, name)) for c in sorted(blocking) if c in state.sim.cubes)
        return frozenset(found)
