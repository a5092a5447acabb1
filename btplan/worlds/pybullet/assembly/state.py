"""The assembly's scene state: where each part is, which way it faces, who grips it.

Everything above (motions, skills, conditions, agents, the world) reads the scene
through this object, and every answer is measured on the simulation: a part lies in a
place when its pose is there, faces up when its own z axis points up, is held when an
arm's grasp constraint carries it off the table, and is mounted when it rests on the
fixture's stack, opening up, with no gripper on it. Nothing here knows the layers above.
"""

from __future__ import annotations

import math

from btplan.errors import WorldError
from btplan.model import Task
from btplan.worlds.pybullet.assembly.geometry import Quat, Vec
from btplan.worlds.pybullet.assembly.panda import Panda
from btplan.worlds.pybullet.assembly.physics import AssemblyPhysics
from btplan.worlds.pybullet.assembly.scene import AssemblyScene, Place
from btplan.worlds.pybullet.sim import HZ

RESTING = 0.012      # metres above its resting height a part on the table may be
UPRIGHT = 0.9        # cosine: a part this close to opening up (or down) faces that way
ON_STACK = 0.025     # metres: a part this far from the fixture's centre is on its stack
FLOOR_BELOW = -0.1   # metres: a part lower than this is off the table


class AssemblyState:
    """The two arms and the parts; see the module docstring."""

    def __init__(self, task: Task, scene: AssemblyScene, gui: bool = False) -> None:
        self.task, self.scene = task, scene
        self.part_names = tuple(sorted(task.objects_of(self._type("part"))))
        self.arm_names = tuple(sorted(task.objects_of(self._type("arm"))))
        self.fixtures = frozenset(task.objects_of(self._type("fixture")))
        self._check()
        self.sim = AssemblyPhysics(scene, gui)  # after the checks: nothing left open
        self.size = {p.name: p.size for p in scene.parts}
        self.lay_out()

    def _type(self, name: str) -> str:
        if name not in self.task.domain.type_parents:
            raise WorldError(f"domain {self.task.domain.name!r} has no type {name!r}: "
                             "the assembly scene needs arm, part, place and fixture")
        return name

    def _check(self) -> None:
        scene = self.scene
        for kind, known in (("arm", {a.name for a in scene.arms}),
                            ("part", {p.name for p in scene.parts}),
                            ("place", {p.name for p in scene.places})):
            for name in self.task.objects_of(kind):
                if name not in known:
                    raise WorldError(f"{name!r} is a {kind} of the problem but not in the scene "
                                     f"{scene.path}; add it as a [[{kind}]]")

    def lay_out(self) -> None:
        """Put every part where the problem's `lies(p, s, f)` says, spread over the place."""
        lying: dict[str, list[tuple[str, str]]] = {}
        for atom in sorted(self.task.initial_state, key=str):
            if atom.predicate == "lies" and len(atom.args) == 3:
                part, place, face = atom.args
                lying.setdefault(place, []).append((part, face))
        for name, parts in lying.items():
            area = self.place(name)
            for k, (part, face) in enumerate(parts):
                (x0, y0), (x1, y1) = area.low, area.high
                y = y0 + (y1 - y0) * (k + 0.5) / len(parts)
                self.lay(part, ((x0 + x1) / 2, y), face, area.below)

    def lay(self, part: str, at: tuple[float, float], face: str, below: bool = False) -> None:
        """Set a part down at `at` with its opening `face` ('up' or 'down')."""
        height = -self.scene.table[2] if below else 0.0
        turn = (1.0, 0.0, 0.0, 0.0) if face == "down" else (0.0, 0.0, 0.0, 1.0)
        self.sim.set_part(part, (at[0], at[1], height + self.size[part][2] / 2 + 0.001), turn)

    def place(self, name: str) -> Place:
        """The place called `name`; a name the scene lacks raises WorldError."""
        place = self.scene.place(name)
        if place is None:
            raise WorldError(f"{name!r} is not a place of the scene {self.scene.path}")
        return place

    @property
    def seconds(self) -> float:
        """Simulated time in seconds: the physics steps taken so far, at 240 Hz."""
        return self.sim.steps / HZ

    def arm(self, name: str) -> Panda:
        """The Panda called `name` (the problem's arms were checked against the scene at start)."""
        return self.sim.arms[name]

    # --- a part's pose -------------------------------------------------------------------

    def pose(self, part: str) -> tuple[Vec, Quat]:
        """A part's position (metres) and orientation (quaternion x, y, z, w), world frame.

        Read from PyBullet once per physics step.
        """
        return self.sim.pose(part)

    def opening(self, part: str) -> Vec:
        """Where the part's opening points (its own z axis), in the world."""
        m = self.sim.p.getMatrixFromQuaternion(self.pose(part)[1])
        return (float(m[2]), float(m[5]), float(m[8]))

    def face(self, part: str) -> str | None:
        """`up` or `down` when the opening points within about 25 degrees of vertical, else None.

        A part lying on its side, or tilted in a hand, faces neither way.
        """
        z = self.opening(part)[2]
        return "up" if z >= UPRIGHT else "down" if z <= -UPRIGHT else None

    def on_table(self, part: str) -> bool:
        """Resting height on the table top, and not on the fixture."""
        (x, y, z), height = self.pose(part)[0], self.size[part][2]
        length, depth, _ = self.scene.table
        return (abs(x) <= length / 2 and abs(y) <= depth / 2 and z <= height / 2 + RESTING
                and not self.over_fixture(part))

    def place_of(self, part: str) -> str | None:
        """The place a part lies in (gripped or not), or None (in the air, on the fixture)."""
        (x, y, z), _ = self.pose(part)
        if z < FLOOR_BELOW:
            return next((p.name for p in self.scene.places if p.below), None)
        if not self.on_table(part):
            return None
        return next((p.name for p in self.scene.places if not p.below and p.contains(x, y)),
                    None)

    def over_fixture(self, part: str) -> bool:
        """Whether the part is above the fixture's top, within ON_STACK metres of its centre.

        Held or not: `mounted` and `stack_top` add what else they need.
        """
        (x, y, z), _ = self.pose(part)
        fx, fy, top = self.scene.fixture
        return math.hypot(x - fx, y - fy) <= ON_STACK and z > top

    def mounted(self, part: str) -> bool:
        """On the fixture's stack, opening up, no gripper on it: in place in the assembly."""
        return self.over_fixture(part) and self.face(part) == "up" and not self.gripping(part)

    def stack_top(self) -> float:
        """The height a part put on the fixture lands at (the top of the parts on it)."""
        top = self.scene.fixture[2]
        for part in self.part_names:
            if self.over_fixture(part) and not self.gripping(part):
                top = max(top, self.pose(part)[0][2] + self.size[part][2] / 2)
        return top

    def free_spot(self, place: str, part: str) -> tuple[float, float] | None:
        """A spot of `place` where `part` lies clear of every other part (None: it is full)."""
        area = self.place(place)
        (x0, y0), (x1, y1) = area.low, area.high
        others = [self.pose(p)[0] for p in self.part_names if p != part]
        spots = [(x0 + (x1 - x0) * (i + 0.5) / 3, y0 + (y1 - y0) * (j + 0.5) / 6)
                 for j in range(6) for i in range(3)]
        spots.sort(key=lambda s: (abs(s[0] - area.center[0]), abs(s[1] - area.center[1])))
        return next((s for s in spots
                     if all(abs(s[0] - o[0]) > 0.14 or abs(s[1] - o[1]) > 0.09 for o in others)),
                    None)

    # --- grips ---------------------------------------------------------------------------

    def gripping(self, part: str) -> list[str]:
        """The arms whose grasp constraint holds `part`, first gripper first."""
        body = self.sim.parts[part]
        arms = [(a.since, name) for name, a in self.sim.arms.items() if a.gripped == body]
        return [name for _, name in sorted(arms)]

    def in_hand(self, arm: str) -> str | None:
        """The part `arm` holds: it gripped it first, and the part is off the table."""
        body = self.arm(arm).gripped
        if body is None:
            return None
        part = self.sim.names[body]
        owners = self.gripping(part)
        if owners[:1] != [arm] or self.on_table(part) or self.mounted(part):
            return None
        return part

    def grasp(self, arm: str, part: str) -> str:
        """'away' when the opening points back along the hand (away from the fingertips)."""
        a, o = self.arm(arm).approach(), self.opening(part)
        return "away" if sum(x * y for x, y in zip(a, o)) < 0 else "toward"

    def close(self) -> None:
        """Disconnect the simulation; the state is unusable afterwards."""
        self.sim.close()
