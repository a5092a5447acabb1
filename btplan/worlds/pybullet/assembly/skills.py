"""The assembly's skills: Pick, Place, Handover and Insert, each a script over ticks.

A skill is a generator of arm motions (motions.py) that the runner steps: each tick it
runs the tick's physics steps, and it ends with SUCCESS the moment the action's
postcondition is measured true on the scene (so the tree never sees a finished action
still running), or with FAILURE when its script gives up. A halted skill leaves the
scene consistent: a part held off the table stays held, any other grip is let go.
Before an arm moves, the other arm, when its hand is empty, goes home out of the way.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Generator

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.worlds.pybullet.arm import Timings
from btplan.worlds.pybullet.assembly import motions as mv
from btplan.worlds.pybullet.assembly.geometry import (
    axis_x,
    axis_y,
    cross,
    down,
    inverse,
    multiply,
    quat_from_axes,
    rotate,
    turn_between,
)
from btplan.worlds.pybullet.assembly.geometry import Quat, Vec
from btplan.worlds.pybullet.assembly.state import AssemblyState
from btplan.worlds.pybullet.sim import HZ

Script = Generator[None, None, Status]
ABOVE = 0.09          # metres above a grasp or set-down point where the hand comes from
GRIP_IN = 0.028       # metres from a part's end to where the fingers take it
LOWEST_TIP = 0.012    # metres above the table the fingertips' centre may go
DROP = 0.003          # metres a part is let go above where it lands


class Scripted:
    """Runs a script one tick of physics at a time; ends when `done` is measured true."""

    def __init__(self, state: AssemblyState, script: Script, done: Callable[[], bool],
                 halt: Callable[[], None]) -> None:
        self.state, self.script, self.done, self.on_halt = state, script, done, halt
        self.substeps = max(1, round(state.scene.tick_seconds * HZ))
        self.status: Status | None = None
        self.started = False
        self.reason = ""  # these skills give no reason for a failure

    def step(self) -> Status:
        """Run the tick's physics steps; SUCCESS the moment `done` is measured true.

        `done` is read after every step and after the script acts on it. A script that ends
        without `done` holding counts as FAILURE; the outcome is repeated on later steps.
        """
        if self.status is not None:
            return self.status
        # `done` is read after the physics moved and again after the script acted (it may
        # have just let go), so the tree never sees the effects before this skill does.
        try:
            if not self.started:
                self.started = True
                next(self.script)
            for _ in range(self.substeps):
                self.state.sim.step()
                if self._finished():
                    return SUCCESS
                next(self.script)
                if self._finished():
                    return SUCCESS
        except StopIteration as finished:
            self.status = SUCCESS if finished.value is SUCCESS and self.done() else FAILURE
            return self.status
        return RUNNING

    def _finished(self) -> bool:
        if self.done():
            self.script.close()
            self.status = SUCCESS
        return self.status is SUCCESS

    def halt(self) -> None:
        """Stop the script; if the action had not ended, let go of parts not held off the table."""
        self.script.close()
        if self.status is None:
            self.on_halt()


def let_go_unless_held(state: AssemblyState) -> None:
    """After a halt: keep a part held off the table, open any other grip."""
    for name in state.arm_names:
        panda = state.arm(name)
        if state.in_hand(name) is None:
            panda.open()
    state.sim.moved()


def clear_others(state: AssemblyState, timings: Timings, *acting: str
                 ) -> Generator[None, None, None]:
    """Let go of parts set down but still gripped (Place ends as soon as the part lies
    there), send every other arm with an empty hand home, out of the shared space; an
    acting arm down among the parts gets clear of them first."""
    for name in state.arm_names:
        if state.arm(name).gripped is not None and state.in_hand(name) is None:
            yield from mv.open_hand(state, name)
    for name in state.arm_names:
        if name not in acting and state.arm(name).gripped is None:
            yield from mv.go_home(state, timings, name)
    for name in acting:
        yield from mv.back_off(state, timings, name)


def grasp_point(state: AssemblyState, arm: str, part: str) -> Vec:
    """Near the end of the part closest to the arm's base, on its long axis."""
    (cx, cy, cz), turn = state.pose(part)
    u = axis_x(turn)
    bx, by = state.arm(arm).base
    sign = -1.0 if (cx + u[0] - bx) ** 2 + (cy + u[1] - by) ** 2 > \
        (cx - u[0] - bx) ** 2 + (cy - u[1] - by) ** 2 else 1.0
    s = state.size[part][0] / 2 - GRIP_IN
    return (cx + sign * s * u[0], cy + sign * s * u[1], max(cz, LOWEST_TIP))


def hand_down_along(turn: Quat) -> list[Quat]:
    """Both hand orientations pointing down with the fingers closing across the part."""
    y = axis_y(turn)
    yaw = math.atan2(-y[0], y[1])
    return [down(yaw), down(yaw + math.pi)]


def pick(state: AssemblyState, timings: Timings, part: str, arm: str) -> Script:
    """Reach above the part, descend, close on it, lift it off the table."""
    yield from clear_others(state, timings, arm)
    at = grasp_point(state, arm, part)
    above = (at[0], at[1], at[2] + ABOVE)
    for turn in hand_down_along(state.pose(part)[1]):
        if mv.solve(state, timings, arm, at, turn) is None:
            continue
        yield from mv.open_hand(state, arm)
        if not (yield from mv.reach(state, timings, arm, above, turn)):
            continue
        yield from mv.slide(state, timings, arm, at, turn)
        if (yield from mv.close_on(state, arm, part)):
            yield from mv.slide(state, timings, arm, above, turn)
            return SUCCESS
        yield from mv.open_hand(state, arm)
        yield from mv.slide(state, timings, arm, above, turn)
    return FAILURE


def set_down(state: AssemblyState, timings: Timings, arm: str, part: str,
             center: Vec) -> Script:
    """Turn the hand to point down, carry the part's centre above `center`, lower, open."""
    panda = state.arm(arm)
    tip, hand = panda.tip()
    pc = state.pose(part)[0]
    options = []
    for turn in rolled(turn_between(panda.approach(), (0.0, 0.0, -1.0)), (0.0, 0.0, -1.0)):
        offset = rotate(turn, (pc[0] - tip[0], pc[1] - tip[1], pc[2] - tip[2]))
        target = (center[0] - offset[0], center[1] - offset[1], center[2] - offset[2])
        options.append((target, multiply(turn, hand)))
    chosen = solvable(state, timings, arm, options)
    if chosen is None:
        return FAILURE
    target, final = chosen
    above = (target[0], target[1], target[2] + ABOVE)
    if not (yield from mv.reach(state, timings, arm, above, final, part)):
        return FAILURE
    yield from mv.slide(state, timings, arm, target, final)
    yield from mv.open_hand(state, arm)
    yield from mv.pause(0.2)
    return SUCCESS


def rolled(turn: Quat, axis: Vec, quarters: int = 2) -> list[Quat]:
    """`turn`, then `turn` followed by a quarter (or half) turn about `axis`, and so on:
    the same approach with the hand rolled, one of which the wrist's limits allow."""
    out = []
    for k in range(quarters):
        angle = 2 * math.pi * k / quarters
        s = math.sin(angle / 2)
        out.append(multiply((axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)), turn))
    return out


def solvable(state: AssemblyState, timings: Timings, arm: str,
             options: list[tuple[Vec, Quat]]) -> tuple[Vec, Quat] | None:
    """The first (tip, orientation) the arm can take, by IK."""
    return next((o for o in options if mv.solve(state, timings, arm, *o) is not None), None)


def insert(state: AssemblyState, timings: Timings, part: str, arm: str) -> Script:
    """Set the part on the fixture's stack, opening up, and let go."""
    yield from clear_others(state, timings, arm)
    fx, fy, _ = state.scene.fixture
    center = (fx, fy, state.stack_top() + state.size[part][2] / 2 + DROP)
    return (yield from set_down(state, timings, arm, part, center))


def place(state: AssemblyState, timings: Timings, part: str, arm: str, where: str) -> Script:
    """Put the part down at a free spot of a place, as it is held."""
    yield from clear_others(state, timings, arm)
    spot = state.free_spot(where, part)
    if spot is None:
        return FAILURE
    center = (spot[0], spot[1], state.size[part][2] / 2 + DROP)
    return (yield from set_down(state, timings, arm, part, center))


def handover(state: AssemblyState, timings: Timings, part: str, giver: str,
             taker: str) -> Script:
    """The giver holds the part out, fingers toward the taker; the taker takes its other
    end from the opposite side, and the giver lets go: the part turns over relative to
    the gripper that holds it."""
    yield from clear_others(state, timings, giver)
    g, t = state.arm(giver), state.arm(taker)
    base_g, base_t = g.base, t.base
    dx, dy = base_t[0] - base_g[0], base_t[1] - base_g[1]
    norm = math.hypot(dx, dy)
    d = (dx / norm, dy / norm, 0.0)
    tip, hand = g.tip()
    center, turn = state.pose(part)
    in_hand = (rotate(inverse(hand), sub(center, tip)), multiply(inverse(hand), turn))
    out = state.scene.handover
    # The giver's hand may roll by quarter turns about the handover direction; the first
    # roll that both arms can take (the taker's grasp predicted from the part's pose in
    # the giver's hand) is used.
    chosen = None
    for roll in rolled(turn_between(g.approach(), d), d, 4):
        held = multiply(roll, hand)
        if mv.solve(state, timings, giver, out, held) is None:
            continue
        seen = (add(out, rotate(held, in_hand[0])), multiply(held, in_hand[1]))
        if solvable(state, timings, taker, take_options(state, part, seen, out, d)):
            chosen = held
            break
    if chosen is None or not (yield from mv.reach(state, timings, giver, out, chosen, part)):
        return FAILURE
    yield from mv.pause(0.2)
    taking = solvable(state, timings, taker,
                      take_options(state, part, state.pose(part), g.tip()[0], d))
    if taking is None:
        return FAILURE
    grip, take = taking
    before = (grip[0] + ABOVE * d[0], grip[1] + ABOVE * d[1], grip[2] + ABOVE * d[2])
    if not (yield from mv.reach(state, timings, taker, before, take, part)):
        return FAILURE
    yield from mv.slide(state, timings, taker, grip, take)
    if not (yield from mv.close_on(state, taker, part)):
        yield from mv.open_hand(state, taker)
        return FAILURE
    yield from mv.open_hand(state, giver)
    return SUCCESS


def take_options(state: AssemblyState, part: str, pose: tuple[Vec, Quat], held_at: Vec,
                 d: Vec) -> list[tuple[Vec, Quat]]:
    """Where and how the taker grips a part held out at `pose`: the end the giver does not
    hold, fingers pointing back at the giver (along -d), closing across the part."""
    center, turn = pose
    u = axis_x(turn)
    if sum((c - h) * x for c, h, x in zip(center, held_at, u)) < 0:
        u = (-u[0], -u[1], -u[2])
    s = state.size[part][0] / 2 - GRIP_IN
    grip = add(center, (s * u[0], s * u[1], s * u[2]))
    toward = (-d[0], -d[1], -d[2])
    y = axis_y(turn)
    return [(grip, quat_from_axes(cross(side, toward), side, toward))
            for side in (y, (-y[0], -y[1], -y[2]))]


def add(a: Vec, b: Vec) -> Vec:
    """The sum a + b: a point moved by an offset (metres, world frame)."""
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a: Vec, b: Vec) -> Vec:
    """The difference a - b: the offset from point b to point a (metres, world frame)."""
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
