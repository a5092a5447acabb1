"""The domain's conditions, measured on the scene every time they are asked.

Nothing is read from a stored symbolic state, so a change made by an external agent is
seen on the next tick. `blocks(c, t)` re-plans a stale trajectory before checking it.
"""

from __future__ import annotations

from btplan.errors import WorldError
from btplan.model import Atom
from btplan.worlds.pybullet.routes import Routes

Key = tuple[str, tuple[str, ...]]


class Conditions:
    """`check` for one condition, `facts` for the whole state (the planner's view)."""

    def __init__(self, routes: Routes, assumed: frozenset[Atom]) -> None:
        self.routes, self.state = routes, routes.state
        self.assumed = assumed

    def check(self, key: Key) -> bool:
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
            found = self.routes.blockers(args[1])
            return bool(found) if args[0] == "_" else args[0] in found
        if name == "route":
            traj = state.trajectories.get(args[1])
            return traj is not None and traj.target == args[0]
        raise WorldError(f"the PyBullet world cannot evaluate the condition {name!r}")

    def facts(self) -> frozenset[Atom]:
        """Every condition of the domain's vocabulary that holds now, as atoms."""
        state = self.state
        found: set[Atom] = set(self.assumed)
        locations = [*state.cube_names, *(r.name for r in state.scene.regions), *sorted(state.poses)]
        found.update(Atom("near", (n,)) for n in locations if state.is_near(n))
        held = state.in_hand()
        found.add(Atom("hand_empty", ()) if held is None else Atom("holding", (held,)))
        found.update(Atom("on", (c, p)) for c in state.cube_names for p in locations
                     if state.on(c, p))
        for name in sorted(state.trajectories):
            traj = state.trajectories[name]
            found.add(Atom("route", (traj.target, name)))
            if traj.stale(state.base, traj.goal, state.layout()) or not state.present(traj.target):
                blocking = self.routes.last_blockers.get(name, frozenset())  # check() measures it
            else:
                blocking = self.routes.blockers(name)
            found.update(Atom("blocks", (c, name)) for c in sorted(blocking) if c in state.sim.cubes)
        return frozenset(found)
