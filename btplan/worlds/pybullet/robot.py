"""The mobile manipulator: a Husky base carrying a Franka Panda arm with its two fingers.

Both models ship with pybullet_data. The base is moved kinematically (its pose is set on
every physics substep, so it follows an OMPL path exactly); the arm and the fingers are
driven by joint position control and move only when the physics is stepped. Reaches
come from PyBullet's IK with null-space limits and a rest pose, so that solutions stay
near a sane elbow-up posture, and are accepted only when forward kinematics confirms
them and the arm then touches nothing. A grasped cube is held by the fingers' contact
and friction plus a fixed constraint that is created only once both fingers touch it and
removed as soon as they open, as PyBullet's own grasping demos do.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from btplan.worlds.pybullet.motion import Pose2

HUSKY_SCALE = 0.6
BASE_Z = 0.08
MOUNT = (0.12, 0.0, 0.325)          # the arm's base on the Husky's top plate, base frame
ARM = tuple(range(7))
FINGERS = (9, 10)
HAND = 8
TIP = 11                            # panda_grasptarget: between the finger pads
LOWER = (-2.9671, -1.8326, -2.9671, -3.0718, -2.9671, -0.0175, -2.9671)
UPPER = (2.9671, 1.8326, 2.9671, -0.0698, 2.9671, 3.7525, 2.9671)
REST = (0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.785)
"""The null-space rest pose: elbow up, hand pointing down in front of the base."""
CARRY = (0.0, -1.2, 0.0, -2.9, 0.0, 1.9, 0.785)
"""The safe pose: the arm folded over the base, inside the base's collision disc."""
FORCES = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)
OPEN, SHUT = 0.04, 0.0
FINGER_FORCE = 15.0
TOUCH = 0.005                       # metres: a finger this close to a held cube touches it
CONTACT = 0.0005                    # metres: and this close when the grasp is made
HELD_MARGIN = 0.04                  # metres: a held cube's reach beyond the fingers
IK_TOLERANCE = 0.01                 # metres between the IK target and where the tip ends up
DOWN = (math.pi, 0.0, 0.0)          # roll-pitch-yaw of a hand pointing at the floor


class Robot:
    """The Husky and the Panda in one PyBullet client; see the module docstring."""

    def __init__(self, p: Any, client: int, floor: int) -> None:
        self.p, self.client = p, client
        self.husky = int(p.loadURDF("husky/husky.urdf", [0, 0, BASE_Z], globalScaling=HUSKY_SCALE,
                                    useFixedBase=True, physicsClientId=client))
        # No self-collision: IK with a rest pose keeps the arm clear of itself, and checking
        # it on every physics step would cost a third of the step.
        self.arm = int(p.loadURDF("franka_panda/panda.urdf", list(MOUNT), useFixedBase=True,
                                  physicsClientId=client))
        for link in range(-1, p.getNumJoints(self.husky, physicsClientId=client)):
            for arm_link in range(-1, p.getNumJoints(self.arm, physicsClientId=client)):
                p.setCollisionFilterPair(self.husky, self.arm, link, arm_link, 0,
                                         physicsClientId=client)
        for link in range(-1, p.getNumJoints(self.husky, physicsClientId=client)):
            # The base is moved kinematically: its wheels resting in the floor would only
            # add contacts for the solver. It still collides with the cubes.
            p.setCollisionFilterPair(self.husky, floor, link, -1, 0, physicsClientId=client)
        for finger in FINGERS:
            p.changeDynamics(self.arm, finger, lateralFriction=1.5, spinningFriction=0.01,
                             physicsClientId=client)
        self.pose: Pose2 = (0.0, 0.0, 0.0)
        self.grip: int | None = None          # the grasp constraint, while one exists
        self.gripped: int | None = None       # the body it holds
        self.set_arm(CARRY)
        self.command(CARRY)
        self.fingers(OPEN)
        for finger in FINGERS:
            p.resetJointState(self.arm, finger, OPEN, physicsClientId=client)

    # --- the base ------------------------------------------------------------------------

    def set_base(self, pose: Pose2) -> None:
        """Put the base (and the arm on it) at `pose`; the physics carries a held cube along."""
        p, (x, y, yaw) = self.p, pose
        if self.gripped is not None:
            self._carry(self.pose, pose)
        self.pose = pose
        turn = p.getQuaternionFromEuler([0.0, 0.0, yaw])
        p.resetBasePositionAndOrientation(self.husky, [x, y, BASE_Z], turn,
                                          physicsClientId=self.client)
        c, s = math.cos(yaw), math.sin(yaw)
        mount = [x + c * MOUNT[0] - s * MOUNT[1], y + s * MOUNT[0] + c * MOUNT[1], MOUNT[2]]
        p.resetBasePositionAndOrientation(self.arm, mount, turn, physicsClientId=self.client)

    def _carry(self, old: Pose2, new: Pose2) -> None:
        """Move a gripped cube with the base: the teleport is the base's, not the grasp's."""
        p = self.p
        turn_old = p.getQuaternionFromEuler([0.0, 0.0, old[2]])
        turn_new = p.getQuaternionFromEuler([0.0, 0.0, new[2]])
        assert self.gripped is not None
        pos, orn = p.getBasePositionAndOrientation(self.gripped, physicsClientId=self.client)
        inv_pos, inv_orn = p.invertTransform([old[0], old[1], 0.0], turn_old)
        rel_pos, rel_orn = p.multiplyTransforms(inv_pos, inv_orn, pos, orn)
        pos, orn = p.multiplyTransforms([new[0], new[1], 0.0], turn_new, rel_pos, rel_orn)
        p.resetBasePositionAndOrientation(self.gripped, pos, orn, physicsClientId=self.client)

    # --- the arm -------------------------------------------------------------------------

    def joints(self) -> tuple[float, ...]:
        """The seven arm joints' angles (radians) as the physics has them, not the targets."""
        states = self.p.getJointStates(self.arm, list(ARM), physicsClientId=self.client)
        return tuple(float(s[0]) for s in states)

    def set_arm(self, q: Sequence[float], speeds: Sequence[float] | None = None) -> None:
        """Teleport the arm's joints (collision checks and start-up only, never while acting).

        One call for the seven joints: collision checks of arm motions make thousands.
        """
        self.p.resetJointStatesMultiDof(
            self.arm, list(ARM), [[v] for v in q],
            targetVelocities=[[v] for v in (speeds if speeds is not None else [0.0] * 7)],
            physicsClientId=self.client)

    def arm_state(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """Joint angles and speeds, so that a collision check can put the arm back as it was
        (a check in the middle of a motion must not stop it)."""
        states = self.p.getJointStates(self.arm, list(ARM), physicsClientId=self.client)
        return tuple(float(s[0]) for s in states), tuple(float(s[1]) for s in states)

    def restore(self, state: tuple[tuple[float, ...], tuple[float, ...]]) -> None:
        """Put the arm back as `arm_state` saw it, joint speeds included.

        A collision check in the middle of a motion thus leaves the motion going.
        """
        self.set_arm(*state)

    def command(self, q: Sequence[float]) -> None:
        """Joint position targets for the arm; reached as the physics is stepped."""
        p = self.p
        p.setJointMotorControlArray(self.arm, list(ARM), p.POSITION_CONTROL,
                                    targetPositions=list(q), forces=list(FORCES),
                                    positionGains=[0.3] * 7, physicsClientId=self.client)

    def fingers(self, width: float) -> None:
        """Position target for each finger, in metres of its travel (OPEN 0.04, SHUT 0).

        Reached as the physics steps, pressing with at most FINGER_FORCE newtons.
        """
        p = self.p
        p.setJointMotorControlArray(self.arm, list(FINGERS), p.POSITION_CONTROL,
                                    targetPositions=[width, width], forces=[FINGER_FORCE] * 2,
                                    physicsClientId=self.client)

    def finger_width(self) -> float:
        """How far the fingers are apart, in metres: both joints' travel summed (0.08 wide open)."""
        states = self.p.getJointStates(self.arm, list(FINGERS), physicsClientId=self.client)
        return float(states[0][0] + states[1][0])

    def tip(self) -> tuple[float, float, float]:
        """The grasp point between the finger pads, world frame, metres.

        Forward kinematics of the joints as they are, so it is correct just after `set_arm` too.
        """
        state = self.p.getLinkState(self.arm, TIP, computeForwardKinematics=True,
                                    physicsClientId=self.client)
        x, y, z = state[4]
        return (float(x), float(y), float(z))

    def tip_yaw(self) -> float:
        """The hand's turn about the vertical, world frame, radians.

        A put-down lowers the cube with the yaw it was grasped with.
        """
        state = self.p.getLinkState(self.arm, TIP, computeForwardKinematics=True,
                                    physicsClientId=self.client)
        return float(self.p.getEulerFromQuaternion(state[5])[2])

    def solve_ik(self, target: Sequence[float], yaw: float) -> tuple[float, ...] | None:
        """Joint angles that put the finger tip at `target`, hand down and turned by `yaw`.

        Null-space IK (limits, ranges, the rest pose) keeps the elbow up; the answer is
        checked by forward kinematics, and None means the target is out of reach.
        """
        p = self.p
        saved = self.arm_state()
        orn = p.getQuaternionFromEuler([DOWN[0], DOWN[1], yaw])
        ranges = [u - lo for lo, u in zip(LOWER, UPPER)]
        try:
            self.set_arm(REST)
            q = p.calculateInverseKinematics(
                self.arm, TIP, list(target), orn, lowerLimits=[*LOWER, 0.0, 0.0],
                upperLimits=[*UPPER, OPEN, OPEN], jointRanges=[*ranges, OPEN, OPEN],
                restPoses=[*REST, OPEN, OPEN], maxNumIterations=60, residualThreshold=1e-4,
                physicsClientId=self.client)
            solution = tuple(float(v) for v in q[:7])
            if any(not lo - 1e-3 <= v <= u + 1e-3 for v, lo, u in zip(solution, LOWER, UPPER)):
                return None
            self.set_arm(solution)
            if math.dist(self.tip(), target) > IK_TOLERANCE:
                return None
            return solution
        finally:
            self.restore(saved)

    def arm_touches(self, q: Sequence[float], bodies: Sequence[int], floor: int | None,
                    restore: bool = True) -> bool:
        """Whether the arm at `q` touches one of `bodies` or (apart from its base) the floor.

        With `restore=False` the arm is left at `q`: a caller checking many poses in a row
        puts it back once, at the end (`arm_state`, `restore`).
        """
        p = self.p
        saved = self.arm_state() if restore else None
        try:
            self.set_arm(q)
            for body in bodies:
                if p.getClosestPoints(self.arm, body, 0.0, physicsClientId=self.client):
                    return True
                # A held cube hangs between the fingers: keep the hand that far from things.
                if self.gripped is not None and any(
                        p.getClosestPoints(self.arm, body, HELD_MARGIN, linkIndexA=link,
                                           physicsClientId=self.client)
                        for link in (HAND, *FINGERS)):
                    return True
            if floor is not None:
                hits = p.getClosestPoints(self.arm, floor, 0.0, physicsClientId=self.client)
                if any(1 <= hit[3] < TIP for hit in hits):
                    return True
            return False
        finally:
            if saved is not None:
                self.restore(saved)

    # --- grasping ------------------------------------------------------------------------

    def touching(self, body: int, within: float = TOUCH) -> tuple[bool, bool]:
        """Whether each finger touches `body` (closest points, so it is never out of date)."""
        p = self.p
        return tuple(bool(p.getClosestPoints(self.arm, body, within, linkIndexA=f,
                                             physicsClientId=self.client))
                     for f in FINGERS)  # type: ignore[return-value]

    def holds(self, body: int) -> bool:
        """Both fingers on the cube and closed on it: what holding means, read from the scene."""
        return all(self.touching(body)) and self.finger_width() < 2 * OPEN - 0.005

    def attach(self, body: int) -> bool:
        """Create the grasp constraint, but only when both fingers touch the cube."""
        if self.grip is not None or not all(self.touching(body, CONTACT)):
            return self.grip is not None and self.gripped == body
        self.grip = grasp(self.p, self.client, self.arm, body)
        self.gripped = body
        return True

    def detach(self) -> None:
        """Remove the grasp constraint (the fingers opened, or the cube was taken away)."""
        release(self.p, self.client, self.arm, self.grip, self.gripped)
        self.grip = self.gripped = None

    def slip(self) -> None:
        """The grip fails: no constraint, and the fingers give way a little; the cube falls."""
        self.detach()
        width = self.finger_width() / 2
        self.fingers(min(OPEN, width + 0.01))
        for finger in FINGERS:
            self.p.resetJointState(self.arm, finger, min(OPEN, width + 0.01),
                                   physicsClientId=self.client)

    def open(self) -> None:
        """Remove the grasp constraint and command the fingers open.

        A held cube falls as the physics steps; nothing waits for the fingers here.
        """
        self.detach()
        self.fingers(OPEN)


def grasp(p: Any, client: int, arm: int, body: int) -> int:
    """Fix `body` to the hand where it is now, and hold the fingers where they met it.

    The constraint alone carries the body: the fingers' contacts with it are switched
    off, since contacts fought against the constraint would let the fingers work their way
    into the body or pry it open. The fingers stay exactly where they are: pressed in,
    they would pop the body away when the contacts come back at release.
    """
    hand_pos, hand_orn = p.getLinkState(arm, HAND, physicsClientId=client)[:2]
    pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=client)
    inv_pos, inv_orn = p.invertTransform(hand_pos, hand_orn)
    rel_pos, rel_orn = p.multiplyTransforms(inv_pos, inv_orn, pos, orn)
    grip = int(p.createConstraint(arm, HAND, body, -1, p.JOINT_FIXED, [0, 0, 0], rel_pos,
                                  [0, 0, 0], rel_orn, physicsClientId=client))
    p.changeConstraint(grip, maxForce=300.0, erp=0.8, physicsClientId=client)
    _finger_contacts(p, client, arm, body, False)
    where = [s[0] for s in p.getJointStates(arm, list(FINGERS), physicsClientId=client)]
    p.setJointMotorControlArray(arm, list(FINGERS), p.POSITION_CONTROL,
                                targetPositions=where, forces=[FINGER_FORCE] * 2,
                                physicsClientId=client)
    return grip


def release(p: Any, client: int, arm: int, grip: int | None, body: int | None) -> None:
    """Undo `grasp`: remove the constraint and give the fingers their contacts back."""
    if grip is not None:
        p.removeConstraint(grip, physicsClientId=client)
    if body is not None:
        _finger_contacts(p, client, arm, body, True)


def _finger_contacts(p: Any, client: int, arm: int, body: int, enabled: bool) -> None:
    for link in (HAND, *FINGERS):
        p.setCollisionFilterPair(arm, body, link, -1, int(enabled), physicsClientId=client)
