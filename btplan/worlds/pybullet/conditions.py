"""The domain's conditions, measured on the scene every time they are asked.

Nothing is read from a stored symbolic state, so a change made by an external agent is
seen on the next tick. `free(t)` re-plans a stale trajectory before checking it.
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
            return args[0] == state.clearing_now or state.is_near(args[0])
        if name == "holding":
            return args[0] != state.clearing_now and state.lifted(args[0])
        if name == "hand_empty":
            # The complement of holding: fingers closing on a cube still on the floor
            # are not holding it yet, and the hand is not yet taken.
            held = state.held
            return held is None or held == state.clearing_now or not state.lifted(held)
        if name == "on":
            return state.on(args[0], args[1])
        if name == "free":
            return self.routes.free(args[0])
        if name == "route":
            traj = state.trajectories.get(args[1])
            return traj is not None and traj.target == args[0]
        if name == "blocks":
            traj = state.trajectories.get(args[1])
            return traj is not None and args[0] in state.blockers(traj)
        raise WorldError(f"the PyBullet world cannot evaluate the condition {name!r}")

    def facts(self) -> frozenset[Atom]:
        """Every condition of the domain's vocabulary that holds now, as atoms."""
        state = self.state
        found: set[Atom] = set(self.assumed)
        locations = [*state.cube_names, *(r.name for r in state.scene.regions), *sorted(state.poses)]
        found.update(Atom("near", (n,)) for n in locations
                     if n == state.clearing_now or state.is_near(n))
        held = state.held
        if held is None or held == state.clearing_now or not state.lifted(held):
            found.add(Atom("hand_empty", ()))
        else:
            found.add(Atom("holding", (held,)))
        found.update(Atom("on", (c, p)) for c in state.cube_names for p in locations
                     if state.on(c, p))
        for name in sorted(state.trajectories):
            traj = state.trajectories[name]
            found.add(Atom("route", (traj.target, name)))
            if traj.stale(state.base, traj.goal, state.layout()) or not state.present(traj.target):
                free = self.routes.last_free.get(name, False)  # check(free(t)) measures it
            else:
                free = self.routes.last_free[name] = not state.blockers(traj)
            if free:
                found.add(Atom("free", (name,)))
        return frozenset(found)
