"""One Franka Panda fixed on the table: joints, IK for any hand orientation, its grasp.

The joint and finger constants are the mobile robot's (robot.py); what differs is a
fixed base and hands that point sideways as well as down (a handover). A grasp is held
by the fingers' contact plus a fixed constraint that is made only once both fingers
touch the part and removed as soon as they open. The physics step at which it was made
is kept: while both arms grip one part, it still belongs to the one that gripped first.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from btplan.worlds.pybullet.assembly.geometry import Quat, Vec
from btplan.worlds.pybullet.robot import (
    ARM,
    CONTACT,
    FINGER_FORCE,
    FINGERS,
    FORCES,
    LOWER,
    OPEN,
    TIP,
    TOUCH,
    UPPER,
    grasp,
    release,
)

Q = tuple[float, ...]

HOME = (0.0, -0.7, 0.0, -2.5, 0.0, 1.8, 0.785)
"""Out of the way: the hand raised close to the arm's own base."""
REST = (0.0, -0.2, 0.0, -2.2, 0.0, 2.0, 0.785)
"""The null-space rest pose of IK: elbow up, the hand in front of the base."""
SEEDS = ((0.0, -0.5, 0.0, -2.6, 0.0, 1.0, 2.356), (0.0, -0.5, 0.0, -2.6, 0.0, 1.0, -0.785))
"""More starts for IK: the wrist tilted back and turned either way, for a hand held out
sideways that PyBullet's IK does not find from the rest pose (joint limits)."""
IK_TOLERANCE = 0.008     # metres between the IK target and where the tip ends up
IK_TURN = 0.1            # radians between the asked and the reached hand orientation


class Panda:
    """A fixed Panda arm with its two fingers; see the module docstring."""

    def __init__(self, p: Any, client: int, name: str, base: Vec) -> None:
        self.p, self.client, self.name = p, client, name
        x, y, yaw = base
        self.base = (x, y)
        self.body = int(p.loadURDF("franka_panda/panda.urdf", [x, y, 0.0],
                                   p.getQuaternionFromEuler([0.0, 0.0, yaw]),
                                   useFixedBase=True, physicsClientId=client))
        for finger in FINGERS:
            p.changeDynamics(self.body, finger, lateralFriction=1.5, spinningFriction=0.01,
                             physicsClientId=client)
        self.grip: int | None = None        # the grasp constraint, while one exists
        self.gripped: int | None = None     # the body it holds
        self.since = 0                      # the physics step the grasp was made at
        self.set_arm(HOME)
        self.command(HOME)
        self.fingers(OPEN)
        for finger in FINGERS:
            p.resetJointState(self.body, finger, OPEN, physicsClientId=client)

    # --- joints --------------------------------------------------------------------------

    def joints(self) -> Q:
        """The seven arm joints' angles (radians) as the physics has them, not the targets."""
        states = self.p.getJointStates(self.body, list(ARM), physicsClientId=self.client)
        return tuple(float(s[0]) for s in states)

    def set_arm(self, q: Sequence[float]) -> None:
        """Teleport the joints: collision checks and start-up only, never while acting."""
        for joint, value in zip(ARM, q):
            self.p.resetJointState(self.body, joint, value, physicsClientId=self.client)

    def command(self, q: Sequence[float]) -> None:
        """Joint position targets (radians) for the arm, reached as the physics steps.

        Forces and gains are the mobile arm's, so both worlds' arms move alike.
        """
        p = self.p
        p.setJointMotorControlArray(self.body, list(ARM), p.POSITION_CONTROL,
                                    targetPositions=list(q), forces=list(FORCES),
                                    positionGains=[0.3] * 7, physicsClientId=self.client)

    def fingers(self, width: float) -> None:
        """Position target per finger, in metres of travel (OPEN 0.04, SHUT 0).

        Reached as the physics steps, pressing with at most FINGER_FORCE newtons.
        """
        p = self.p
        p.setJointMotorControlArray(self.body, list(FINGERS), p.POSITION_CONTROL,
                                    targetPositions=[width, width], forces=[FINGER_FORCE] * 2,
                                    physicsClientId=self.client)

    def finger_width(self) -> float:
        """How far the fingers are apart, in metres: both joints' travel summed (0.08 wide open)."""
        states = self.p.getJointStates(self.body, list(FINGERS), physicsClientId=self.client)
        return float(states[0][0] + states[1][0])

    # --- the hand ------------------------------------------------------------------------

    def tip(self) -> tuple[Vec, Quat]:
        """Where the point between the finger pads is, and the hand's orientation."""
        state = self.p.getLinkState(self.body, TIP, computeForwardKinematics=True,
                                    physicsClientId=self.client)
        (x, y, z), (a, b, c, d) = state[4], state[5]
        return (float(x), float(y), float(z)), (float(a), float(b), float(c), float(d))

    def approach(self) -> Vec:
        """The way the fingers point (the hand's z axis)."""
        matrix = self.p.getMatrixFromQuaternion(self.tip()[1])
        return (float(matrix[2]), float(matrix[5]), float(matrix[8]))

    def solve_ik(self, target: Vec, orientation: Quat, near: Q | None = None) -> Q | None:
        """Joints that put the tip at `target` with the hand turned as `orientation`.

        Null-space IK (limits, a rest pose) keeps the elbow up; forward kinematics must
        confirm the answer, or it is None (out of reach). `near` (for short straight moves)
        starts from and stays close to those joints instead of the rest pose, so that a
        joint-space interpolation between two answers keeps the tip on its line.
        """
        saved = self.joints()
        try:
            if near is not None:
                return self._ik(target, orientation, near)
            # From the elbow-up rest pose first, then from where the arm is, then SEEDS.
            for rest in (REST, saved, *SEEDS):
                found = self._ik(target, orientation, rest)
                if found is not None:
                    return found
            return None
        finally:
            self.set_arm(saved)

    def _ik(self, target: Vec, orientation: Quat, rest: Q) -> Q | None:
        ranges = [u - lo for lo, u in zip(LOWER, UPPER)]
        self.set_arm(rest)
        for _ in range(3):  # a second and third start from the last answer
            q = self.p.calculateInverseKinematics(
                self.body, TIP, list(target), list(orientation),
                lowerLimits=[*LOWER, 0.0, 0.0], upperLimits=[*UPPER, OPEN, OPEN],
                jointRanges=[*ranges, OPEN, OPEN], restPoses=[*rest, OPEN, OPEN],
                maxNumIterations=100, residualThreshold=1e-5, physicsClientId=self.client)
            solution = tuple(min(max(float(v), lo), u) for v, lo, u in zip(q[:7], LOWER, UPPER))
            self.set_arm(solution)
            where, turn = self.tip()
            if math.dist(where, target) <= IK_TOLERANCE and _angle(turn, orientation) <= IK_TURN:
                return solution
        return None

    def touches(self, q: Sequence[float], bodies: Sequence[int], table: int,
                clearance: float = 0.0) -> bool:
        """Whether the arm at `q` comes within `clearance` of one of `bodies`, or touches
        the table with more than its foot."""
        p = self.p
        saved = self.joints()
        try:
            self.set_arm(q)
            if any(p.getClosestPoints(self.body, body, clearance, physicsClientId=self.client)
                   for body in bodies):
                return True
            return any(p.getClosestPoints(self.body, table, 0.0, linkIndexA=link,
                                          physicsClientId=self.client)
                       for link in range(1, TIP))
        finally:
            self.set_arm(saved)

    # --- grasping ------------------------------------------------------------------------

    def touching(self, body: int, within: float = TOUCH) -> bool:
        """Both fingers on `body` (closest points, so never out of date)."""
        return all(self.p.getClosestPoints(self.body, body, within, linkIndexA=f,
                                           physicsClientId=self.client) for f in FINGERS)

    def attach(self, body: int, step: int) -> bool:
        """Make the grasp constraint, but only when both fingers touch the part."""
        if self.grip is not None:
            return self.gripped == body
        if not self.touching(body, CONTACT):
            return False
        self.grip = grasp(self.p, self.client, self.body, body)
        self.gripped, self.since = body, step
        return True

    def detach(self) -> None:
        """Remove the grasp constraint, if any, and give the fingers back their contacts with it."""
        release(self.p, self.client, self.body, self.grip, self.gripped)
        self.grip = self.gripped = None

    def open(self) -> None:
        """Let go: remove the grasp and command the fingers open.

        The part stays or falls as the physics decides; nothing waits for the fingers here.
        """
        self.detach()
        self.fingers(OPEN)


def _angle(a: Quat, b: Quat) -> float:
    """The angle between two orientations."""
    dot = abs(sum(x * y for x, y in zip(a, b)))
    return 2.0 * math.acos(min(1.0, dot))
