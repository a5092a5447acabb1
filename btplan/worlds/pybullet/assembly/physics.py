"""The PyBullet client of an assembly: the table, the fixture, two Pandas and the parts.

Physics is stepped at 240 Hz (sim.HZ). The table top is z = 0 and the floor is the
table's height below it, so a part knocked off the table falls to the floor. Parts are
boxes whose opening (the top face of the box in its own frame) is drawn as a dark
inlay, so which way it faces shows in every picture.
"""

from __future__ import annotations

import contextlib
import importlib
import math
import os
import sys
import time
from typing import Any

from btplan.errors import WorldError
from btplan.worlds.pybullet.assembly.geometry import Quat, Vec
from btplan.worlds.pybullet.assembly.panda import Panda
from btplan.worlds.pybullet.assembly.scene import AssemblyScene
from btplan.worlds.pybullet.sim import HZ, SOLVER_ITERATIONS, quiet_stdout, render

PART_MASS = 0.08     # kilograms


class AssemblyPhysics:
    """Bodies and stepping; what the bodies mean is the state's (state.py)."""

    def __init__(self, scene: AssemblyScene, gui: bool = False) -> None:
        with quiet_stdout((1, 2)):
            p: Any = importlib.import_module("pybullet")
            data: Any = importlib.import_module("pybullet_data")
        if gui and sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
            raise WorldError("--gui needs a display (DISPLAY is not set); run headless instead")
        self.p, self.scene = p, scene
        with quiet_stdout():
            self.client = int(p.connect(p.GUI if gui else p.DIRECT))
        if self.client < 0:
            raise WorldError("could not connect to PyBullet")
        c = self.client
        p.setGravity(0, 0, -9.81, physicsClientId=c)
        p.setTimeStep(1.0 / HZ, physicsClientId=c)
        p.setPhysicsEngineParameter(numSolverIterations=SOLVER_ITERATIONS, physicsClientId=c)
        self.steps = 0
        self.physics_seconds = 0.0
        self.memo: dict[object, object] = {}
        length, depth, height = scene.table
        with quiet_stdout():
            p.setAdditionalSearchPath(data.getDataPath(), physicsClientId=c)
            self.floor = int(p.loadURDF("plane.urdf", [0, 0, -height], physicsClientId=c))
            self.table = self.box((0.0, 0.0, -height / 2), (length, depth, height),
                                  (0.62, 0.5, 0.38))
            fx, fy, top = scene.fixture
            self.fixture = self.box((fx, fy, top / 2), (*scene.fixture_size, top),
                                    (0.35, 0.35, 0.4))
            for place in scene.places:
                if not place.below:
                    (x0, y0), (x1, y1) = place.low, place.high
                    self.box(((x0 + x1) / 2, (y0 + y1) / 2, 0.0005), (x1 - x0, y1 - y0, 0.001),
                             place.color, solid=False)
            self.arms = {a.name: Panda(p, c, a.name, a.base) for a in scene.arms}
        self.parts: dict[str, int] = {}
        for spec in scene.parts:
            self.parts[spec.name] = self.part_body(spec.size, spec.color)
        self.names = {body: name for name, body in self.parts.items()}

    def box(self, center: Vec, size: Vec, color: Vec, solid: bool = True) -> int:
        """A fixed box at `center` with full side lengths `size` (metres).

        `solid=False` makes it visual only: the places' markings on the table top.
        """
        p, c = self.p, self.client
        half = [s / 2 for s in size]
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=c) \
            if solid else -1
        visual = p.createVisualShape(p.GEOM_BOX, halfExtents=half, rgbaColor=[*color, 1.0],
                                     physicsClientId=c)
        return int(p.createMultiBody(0.0, shape, visual, list(center), physicsClientId=c))

    def part_body(self, size: Vec, color: Vec) -> int:
        """A box with a dark inlay on its top face (its opening), parked below the floor."""
        p, c = self.p, self.client
        half = [s / 2 for s in size]
        inlay = [half[0] * 0.7, half[1] * 0.6, 0.001]
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=c)
        visual = p.createVisualShapeArray(
            shapeTypes=[p.GEOM_BOX, p.GEOM_BOX], halfExtents=[half, inlay],
            rgbaColors=[[*color, 1.0], [0.08, 0.08, 0.08, 1.0]],
            visualFramePositions=[[0, 0, 0], [0, 0, half[2] + 0.001]], physicsClientId=c)
        body = int(p.createMultiBody(PART_MASS, shape, visual, [0, 0, -10.0],
                                     physicsClientId=c))
        p.changeDynamics(body, -1, lateralFriction=1.0, spinningFriction=0.01,
                         physicsClientId=c)
        return body

    # --- time ----------------------------------------------------------------------------

    def step(self) -> None:
        """One physics step of 1/240 s, its wall time kept for the statistics.

        What was read of the scene (part poses) is forgotten: it may have changed.
        """
        began = time.perf_counter()
        self.p.stepSimulation(physicsClientId=self.client)
        self.physics_seconds += time.perf_counter() - began
        self.steps += 1
        self.memo.clear()

    def moved(self) -> None:
        """Forget what was read of the scene (something was teleported)."""
        self.memo.clear()

    # --- parts ---------------------------------------------------------------------------

    def pose(self, name: str) -> tuple[Vec, Quat]:
        """A part's position and orientation, read once per physics step."""
        key = ("pose", name)
        if key not in self.memo:
            pos, orn = self.p.getBasePositionAndOrientation(self.parts[name],
                                                            physicsClientId=self.client)
            self.memo[key] = (tuple(float(v) for v in pos), tuple(float(v) for v in orn))
        known: tuple[Vec, Quat] = self.memo[key]  # type: ignore[assignment]
        return known

    def set_part(self, name: str, at: Vec, orientation: Quat) -> None:
        """Teleport a part (start-up and external agents), letting go of any grip on it."""
        body = self.parts[name]
        for arm in self.arms.values():
            if arm.gripped == body:
                arm.open()
        self.p.resetBasePositionAndOrientation(body, list(at), list(orientation),
                                               physicsClientId=self.client)
        self.p.resetBaseVelocity(body, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)
        self.moved()

    def speed(self, name: str) -> float:
        """A part's linear speed in m/s, read fresh each time (it is not kept per step)."""
        linear, _ = self.p.getBaseVelocity(self.parts[name], physicsClientId=self.client)
        return math.sqrt(sum(float(v) ** 2 for v in linear))

    # --- pictures ------------------------------------------------------------------------

    def snapshot(self, width: int = 640, height: int = 400) -> tuple[int, int, bytes]:
        """An RGB picture of the table from the front, both arms in view (software renderer)."""
        p = self.p
        return render(p, self.client, ([0.0, -1.05, 0.72], [0.0, 0.05, 0.24]), (62, 10.0),
                      width, height)

    def close(self) -> None:
        """Disconnect from PyBullet; a client already gone is no error (failed runs close too)."""
        with contextlib.suppress(Exception):
            self.p.disconnect(physicsClientId=self.client)
