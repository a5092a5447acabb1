"""Arm motions of the assembly, as generators that yield once per physics step.

Each goal pose comes from IK; a joint move goes straight when every configuration on
the way is collision-free (checked every arm.CHECK_STEP radians), and through an OMPL
plan in joint space (motion.plan_joints) when it is not. The obstacles are the table,
the fixture, the parts not being handled and the other arm, wherever it stands now:
during a handover the giver is an obstacle for the taker and the other way round.
"""

from __future__ import annotations

import math
import time
from collections.abc import Generator, Sequence

from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.arm import AT, JOINT_SPEED, SETTLE, Timings, straight_free
from btplan.worlds.pybullet.assembly.geometry import Quat, Vec
from btplan.worlds.pybullet.assembly.panda import HOME, Q
from btplan.worlds.pybullet.assembly.state import AssemblyState
from btplan.worlds.pybullet.robot import LOWER, OPEN, SHUT, UPPER
from btplan.worlds.pybullet.sim import HZ

Motion = Generator[None, None, bool]
"""Yields once per physics step; returns whether it got where it was going."""

ARM_ITERATIONS = 250   # RRTConnect iterations for one arm motion (~8 ms each)
BACK_OFF = 0.09        # m the hand moves back along its fingers before it goes home
SLOW = 0.5             # the joint speed of short moves near parts, as a fraction
LOW = 0.25             # m: an empty hand lower than this backs off before the arm moves on
LIFT = 0.12            # m: a part held lower than this is lifted first
CLEARANCE = 0.02       # m: kept from other bodies along an OMPL path


def obstacles(state: AssemblyState, arm: str, *handled: str) -> list[int]:
    """Bodies `arm` must not touch: the fixture, the other arm and the parts not `handled`."""
    sim = state.sim
    own = sim.arms[arm].gripped
    bodies = [sim.fixture] + [a.body for name, a in sim.arms.items() if name != arm]
    return bodies + [body for name, body in sorted(sim.parts.items())
                     if name not in handled and body != own]


def solve(state: AssemblyState, timings: Timings, arm: str, target: Vec,
          orientation: Quat, near: Q | None = None) -> Q | None:
    """IK for `arm`'s tip at `target` (metres, world frame), the hand turned as `orientation`.

    None when out of reach. `near` keeps the answer close to those joints (short straight
    moves); the wall time goes to `timings.ik`.
    """
    began = time.perf_counter()
    try:
        return state.arm(arm).solve_ik(target, orientation, near)
    finally:
        timings.ik += time.perf_counter() - began


def plan(state: AssemblyState, timings: Timings, arm: str, goal: Q, *handled: str
         ) -> list[Q] | None:
    """A collision-free joint path to `goal`: straight if it is free, else OMPL's."""
    began = time.perf_counter()
    panda, table = state.arm(arm), state.sim.table
    bodies = obstacles(state, arm, *handled)

    def free(q: Q) -> bool:
        return not panda.touches(q, bodies, table)

    try:
        start = panda.joints()
        if not free(goal):
            return None
        if straight_free(start, goal, free):
            return [start, goal]
        timings.ompl_solves += 1

        def roomy(q: Q) -> bool:
            return not panda.touches(q, bodies, table, CLEARANCE)

        # A path that only just misses the other arm grazes it when the arm, driven by
        # its motors, lags behind the path: keep a margin, where start and goal allow one.
        valid = roomy if roomy(start) and roomy(goal) else free
        solving = time.perf_counter()
        found = motion.plan_joints(start, goal, valid, LOWER, UPPER, ARM_ITERATIONS)
        timings.ompl += time.perf_counter() - solving
        return None if found is None else list(found.path)
    finally:
        timings.arm_planning += time.perf_counter() - began


def follow(state: AssemblyState, arm: str, path: Sequence[Q], speed: float = 1.0) -> Motion:
    """Command the arm along `path`, then let it settle on the last point."""
    panda = state.arm(arm)
    per_step = JOINT_SPEED * speed / HZ
    for a, b in zip(path, path[1:]):
        n = max(1, math.ceil(max(abs(x - y) for x, y in zip(a, b)) / per_step))
        for k in range(1, n + 1):
            panda.command(tuple(x + (y - x) * k / n for x, y in zip(a, b)))
            yield
    goal = path[-1]
    for _ in range(int(SETTLE * HZ)):
        if max(abs(x - y) for x, y in zip(panda.joints(), goal)) < AT:
            return True
        yield
    return max(abs(x - y) for x, y in zip(panda.joints(), goal)) < 3 * AT


def reach(state: AssemblyState, timings: Timings, arm: str, target: Vec, orientation: Quat,
          *handled: str) -> Motion:
    """Move the tip to `target` turned as `orientation`, planned around the obstacles."""
    goal = solve(state, timings, arm, target, orientation)
    if goal is None:
        return False
    path = plan(state, timings, arm, goal, *handled)
    if path is None:
        return False
    return (yield from follow(state, arm, path))


def slide(state: AssemblyState, timings: Timings, arm: str, target: Vec, orientation: Quat,
          pieces: int = 6) -> Motion:
    """A short straight move of the tip (down onto a part, up off it), slowly, by IK
    waypoints each near the one before; not checked against the part it grasps or sets
    down, on purpose."""
    start, _ = state.arm(arm).tip()
    path = [state.arm(arm).joints()]
    for k in range(1, pieces + 1):
        point = tuple(s + (t - s) * k / pieces for s, t in zip(start, target))
        q = solve(state, timings, arm, point, orientation, path[-1])  # type: ignore[arg-type]
        if q is None:
            return False
        path.append(q)
    return (yield from follow(state, arm, path, SLOW))


def close_on(state: AssemblyState, arm: str, part: str) -> Motion:
    """Close the fingers; True once both touch `part` and the grasp is made."""
    panda, body = state.arm(arm), state.sim.parts[part]
    panda.fingers(SHUT)
    last = panda.finger_width()
    for k in range(int(0.6 * HZ)):
        yield
        if panda.attach(body, state.sim.steps):
            return True
        now = panda.finger_width()
        if now < 0.002 or (k > 12 and abs(now - last) < 1e-5):
            break
        last = now
    return panda.attach(body, state.sim.steps)


def open_hand(state: AssemblyState, arm: str) -> Motion:
    """Let go and open the fingers, for at most 0.3 s, until they are nearly wide open; True."""
    panda = state.arm(arm)
    panda.open()
    state.sim.moved()
    for _ in range(int(0.3 * HZ)):
        yield
        if panda.finger_width() > 2 * OPEN - 0.004:
            break
    return True


def at_home(state: AssemblyState, arm: str) -> bool:
    """Whether every joint is within 3 * AT radians of HOME: then `go_home` has nothing to do."""
    return max(abs(x - y) for x, y in zip(state.arm(arm).joints(), HOME)) < 3 * AT


def back_off(state: AssemblyState, timings: Timings, arm: str) -> Motion:
    """A hand low among the parts gets clear before the arm moves on: an empty one backs
    off along its fingers, one holding a part lifts it straight up (a joint-space move
    from down there could drag the part over the table)."""
    panda = state.arm(arm)
    tip, turn = panda.tip()
    if panda.gripped is not None:
        if tip[2] >= LIFT:
            return True
        return (yield from slide(state, timings, arm, (tip[0], tip[1], LIFT), turn))
    if tip[2] > LOW:
        return True
    a = panda.approach()
    back = (tip[0] - BACK_OFF * a[0], tip[1] - BACK_OFF * a[1], tip[2] - BACK_OFF * a[2])
    return (yield from slide(state, timings, arm, back, turn, 2))


def go_home(state: AssemblyState, timings: Timings, arm: str) -> Motion:
    """Back off (out of whatever the fingers were around), then go home."""
    if at_home(state, arm):
        return True
    panda = state.arm(arm)
    if panda.gripped is None:
        a = panda.approach()
        tip, turn = panda.tip()
        back = (tip[0] - BACK_OFF * a[0], tip[1] - BACK_OFF * a[1], tip[2] - BACK_OFF * a[2])
        yield from slide(state, timings, arm, back, turn, 2)
    path = plan(state, timings, arm, HOME)
    if path is None:  # last resort: straight, as the mobile arm folds itself
        path = [panda.joints(), HOME]
    return (yield from follow(state, arm, path))


def pause(seconds: float) -> Motion:
    """Let the physics run for `seconds` with no command (a part let go lands); always True."""
    for _ in range(int(seconds * HZ)):
        yield
    return True

