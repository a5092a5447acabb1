"""The PyBullet scene: walls, regions, dynamic cubes and the robot, physics and collision queries.

Physics is stepped at 240 Hz, several substeps per tick: cubes fall, rest and are pushed
by contact, the arm moves by joint position control, and a grasped cube is carried by
the fingers. Collision queries for planning (getClosestPoints on probe bodies) do not
step the simulation. Everything is in one PyBullet client, headless unless asked.
"""

from __future__ import annotations

import contextlib
import importlib
import math
import os
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any

from btplan.errors import WorldError
from btplan.worlds.pybullet.motion import Pose2
from btplan.worlds.pybullet.robot import Robot
from btplan.worlds.pybullet.scene import Point, Scene

HZ = 240            # physics steps per simulated second
PARKED_Z = -10.0    # cubes not in the scene (yet, or any more) wait far below the floor
CUBE_MASS = 0.1     # kilograms
SOLVER_ITERATIONS = 15
PROBE_Z = 0.5       # half the height of the base's collision probe (the folded arm is ~0.9 m)
KNOCK_SPEED = 2.0   # m/s given to a knocked cube: it slides off a shelf board and falls


@contextlib.contextmanager
def quiet_stdout(fds: tuple[int, ...] = (1,)) -> Iterator[None]:
    """Send C-level output (fd 1, and fd 2 if asked) to /dev/null.

    URDF loading prints warnings on fd 1, where btplan writes data; importing pybullet
    prints its build date on fd 2, which is only noise.
    """
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(fd) for fd in fds]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        for fd in fds:
            os.dup2(null, fd)
        yield
    finally:
        _flush_c_stdio()  # C printf output still buffered must go to /dev/null, not to us
        for fd, copy in zip(fds, saved):
            os.dup2(copy, fd)
            os.close(copy)
        os.close(null)


def _near(x: float, y: float, boxes: list[tuple[int, tuple[float, float, float, float]]],
          reach: float) -> list[int]:
    """The bodies whose footprint (centre, half sizes) is within `reach` of (x, y).

    Compared without a square root: this runs for every state OMPL checks, and most
    states are far from every body.
    """
    near = []
    for body, (cx, cy, hx, hy) in boxes:
        dx, dy = abs(x - cx) - hx, abs(y - cy) - hy
        if dx > reach or dy > reach or (dx > 0 < dy and dx * dx + dy * dy > reach * reach):
            continue
        near.append(body)
    return near


def _flush_c_stdio() -> None:
    import ctypes

    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None).fflush(None)


class Sim:
    """One PyBullet client holding the scene's bodies."""

    def __init__(self, scene: Scene, gui: bool = False) -> None:
        with quiet_stdout((1, 2)):  # the pybullet module prints its build time on import
            p: Any = importlib.import_module("pybullet")
            pybullet_data: Any = importlib.import_module("pybullet_data")

        self.p = p
        self.scene = scene
        if gui and sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
            raise WorldError("--gui needs a display (DISPLAY is not set); run headless instead")
        with quiet_stdout():
            self.client = p.connect(p.GUI if gui else p.DIRECT)
        if self.client < 0:
            raise WorldError("could not connect to PyBullet" + (" with a window" if gui else ""))
        p.setGravity(0, 0, -9.81, physicsClientId=self.client)
        p.setTimeStep(1.0 / HZ, physicsClientId=self.client)
        # 15 solver iterations instead of 50: cubes rest and stack as well (grasps are held
        # by a constraint), at 40 % less time per step.
        p.setPhysicsEngineParameter(numSolverIterations=SOLVER_ITERATIONS,
                                    physicsClientId=self.client)
        self.steps = 0
        self.physics_seconds = 0.0
        self.outside_changes = 0
        """Physics steps in which someone other than the robot moved a cube."""
        self.controllers: list[Callable[[], None]] = []
        """Called before every physics step: bodies driven by velocity (the agents' pusher)."""
        self._positions: dict[str, tuple[float, float, float]] = {}
        self.memo: dict[object, object] = {}
        """Values derived from the scene (who holds what), valid until it changes."""
        with quiet_stdout():
            p.setAdditionalSearchPath(pybullet_data.getDataPath(), physicsClientId=self.client)
            self.floor = int(p.loadURDF("plane.urdf", physicsClientId=self.client))
            self.robot = Robot(p, self.client, self.floor)
        self.walls = [self._box(w.center, w.size, w.height / 2, (0.55, 0.5, 0.45), z=w.z)
                      for w in scene.walls]
        # Footprints (centre, half sizes) of the solid bodies: a cheap first test, so that
        # PyBullet is only asked about bodies that can touch the probe.
        self.extent: dict[int, tuple[float, float, float, float]] = {
            body: (w.center[0], w.center[1], w.size[0] / 2, w.size[1] / 2)
            for body, w in zip(self.walls, scene.walls)}
        for region in scene.regions:
            half = ((region.high[0] - region.low[0]) / 2, (region.high[1] - region.low[1]) / 2)
            self._box(region.center, (half[0] * 2, half[1] * 2), 0.002, region.color, solid=False)
        size = scene.cube_size
        self.cubes: dict[str, int] = {}
        self.names: dict[int, str] = {}
        for cube in scene.cubes:
            body = self._box((0.0, 0.0), (size, size), size / 2, cube.color, mass=CUBE_MASS)
            p.changeDynamics(body, -1, lateralFriction=1.0, physicsClientId=self.client)
            self.cubes[cube.name] = body
            self.names[body] = cube.name
            self.place_cube(cube.name, cube.at)
        r = scene.robot_radius
        self.probe = self._cylinder(r)
        self.cube_probe = self._box((0.0, 0.0), (size, size), size / 2, None)
        for probe in (self.probe, self.cube_probe):  # queried, never pushing anything
            p.setCollisionFilterGroupMask(probe, -1, 0, 0, physicsClientId=self.client)
        self.set_robot(scene.start)

    # --- bodies --------------------------------------------------------------------------

    def _box(self, center: Point, size: Point, half_height: float,
             color: tuple[float, float, float] | None, solid: bool = True,
             mass: float = 0.0, z: float = 0.0) -> int:
        """A box resting on the floor (or with its underside at `z`); `solid=False` makes
        it visual only (regions)."""
        p = self.p
        half = [size[0] / 2, size[1] / 2, half_height]
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=half, physicsClientId=self.client) \
            if solid else -1
        visual = -1 if color is None else p.createVisualShape(
            p.GEOM_BOX, halfExtents=half, rgbaColor=[*color, 1.0], physicsClientId=self.client)
        return int(p.createMultiBody(mass, shape, visual, [center[0], center[1], z + half_height],
                                     physicsClientId=self.client))

    def _cylinder(self, radius: float) -> int:
        p = self.p
        # As tall as the robot with its arm folded: a shelf the arm would hit blocks the base.
        shape = p.createCollisionShape(p.GEOM_CYLINDER, radius=radius, height=2 * PROBE_Z,
                                       physicsClientId=self.client)
        return int(p.createMultiBody(0.0, shape, -1, [0.0, 0.0, PARKED_Z], physicsClientId=self.client))

    def close(self) -> None:
        """Disconnect from PyBullet; a client already gone is no error (failed runs close too)."""
        with contextlib.suppress(Exception):
            self.p.disconnect(physicsClientId=self.client)

    # --- poses ---------------------------------------------------------------------------

    def set_robot(self, pose: Pose2) -> None:
        """Teleport the base to `pose` (a held cube comes along) and forget what was read."""
        self.robot.set_base(pose)
        self.moved()

    def moved(self) -> None:
        """Forget what was read of the scene: the physics stepped or something was moved.

        Conditions and collision queries read cube positions thousands of times between
        two physics steps; they are read from PyBullet once per step instead.
        """
        self._positions.clear()
        self.memo.clear()

    @property
    def pose(self) -> Pose2:
        """The base's pose (x, y in metres, yaw in radians) as last set.

        The base is moved kinematically, so this is exact, never read back from the physics.
        """
        return self.robot.pose

    def step(self) -> None:
        """One physics step of 1/240 s (its wall time is kept for bench/sim.py)."""
        for control in self.controllers:
            control()
        began = time.perf_counter()
        self.p.stepSimulation(physicsClientId=self.client)
        self.physics_seconds += time.perf_counter() - began
        self.moved()
        self.steps += 1

    def place_cube(self, name: str, at: Point | None) -> None:
        """Set a cube on the floor at `at`, or park it out of the scene when `at` is None.

        This is a teleport (start-up, and the explicit teleport events of tests); a cube
        in the gripper is let go first.
        """
        self.moved()
        body = self.cubes[name]
        if self.robot.gripped == body:
            self.robot.detach()
        z = self.scene.cube_size / 2 if at is not None else PARKED_Z
        x, y = at if at is not None else (0.0, 0.0)
        self.p.resetBasePositionAndOrientation(body, [x, y, z], [0, 0, 0, 1],
                                               physicsClientId=self.client)
        self.p.resetBaseVelocity(body, [0, 0, 0], [0, 0, 0], physicsClientId=self.client)

    def knock(self, name: str, at: Point, toward: Point) -> None:
        """Set a cube on top of what is under `at` (a shelf board, or the floor) and give
        it a horizontal speed towards `toward`: from there on the physics moves it."""
        self.moved()
        body = self.cubes[name]
        if self.robot.gripped == body:
            self.robot.detach()
        top = max((w.z + w.height for w, wall in zip(self.scene.walls, self.walls)
                   if _near(at[0], at[1], [(wall, self.extent[wall])], 0.0)), default=0.0)
        dx, dy = toward[0] - at[0], toward[1] - at[1]
        length = math.hypot(dx, dy)
        self.p.resetBasePositionAndOrientation(
            body, [at[0], at[1], top + self.scene.cube_size / 2 + 0.002], [0, 0, 0, 1],
            physicsClientId=self.client)
        self.p.resetBaseVelocity(body, [dx / length * KNOCK_SPEED, dy / length * KNOCK_SPEED, 0.0],
                                 [0, 0, 0], physicsClientId=self.client)

    def cube_position(self, name: str) -> tuple[float, float, float]:
        """A cube's centre, world frame, metres; read from PyBullet once per physics step.

        A cube out of the scene is parked far below the floor (z = PARKED_Z).
        """
        known = self._positions.get(name)
        if known is None:
            pos, _ = self.p.getBasePositionAndOrientation(self.cubes[name],
                                                          physicsClientId=self.client)
            known = self._positions[name] = (float(pos[0]), float(pos[1]), float(pos[2]))
        return known

    def cube_yaw(self, name: str) -> float:
        """A cube's turn about the vertical, in radians (only grasps ask, so it is not cached)."""
        _, orn = self.p.getBasePositionAndOrientation(self.cubes[name], physicsClientId=self.client)
        return float(self.p.getEulerFromQuaternion(orn)[2])

    def cube_speed(self, name: str) -> float:
        """A cube's speed in m/s, read once per physics step (`resting` asks for each cube)."""
        key = ("speed", name)
        known = self.memo.get(key)
        if not isinstance(known, float):
            linear, _ = self.p.getBaseVelocity(self.cubes[name], physicsClientId=self.client)
            known = self.memo[key] = math.sqrt(sum(v * v for v in linear))
        return known

    def gripper_point(self) -> Point:
        """The finger tip's position projected on the floor (x, y, metres)."""
        x, y, _ = self.robot.tip()
        return (x, y)

    # --- collision queries ---------------------------------------------------------------

    def _hits(self, probe: int, at: tuple[float, float, float], bodies: list[int],
              margin: float) -> bool:
        reach = (self.scene.robot_radius if probe == self.probe else self.scene.cube_size) \
            + margin + 0.02
        near = _near(at[0], at[1], [(body, self.footprint(body)) for body in bodies], reach)
        return bool(near) and self._touches(probe, at, near, margin)

    def _touches(self, probe: int, at: tuple[float, float, float], bodies: list[int],
                 margin: float) -> bool:
        p = self.p
        p.resetBasePositionAndOrientation(probe, at, [0, 0, 0, 1], physicsClientId=self.client)
        return any(p.getClosestPoints(probe, body, margin, physicsClientId=self.client)
                   for body in bodies)

    def base_checker(self, cubes: list[str]) -> Callable[[float, float], bool]:
        """`base_free(x, y, cubes)` for the many states of one OMPL solve: nothing moves
        while OMPL plans, so the bodies and their footprints are looked up once."""
        r = self.scene.robot_radius
        x0, x1, y0, y1 = self.scene.bounds
        boxes = [(body, self.footprint(body)) for body in self.walls + [self.cubes[c] for c in cubes]]

        def free(x: float, y: float) -> bool:
            if not (x0 + r <= x <= x1 - r and y0 + r <= y <= y1 - r):
                return False
            near = _near(x, y, boxes, r + 0.02)
            return not (near and self._touches(self.probe, (x, y, PROBE_Z), near, 0.0))

        return free

    def footprint(self, body: int) -> tuple[float, float, float, float]:
        """Centre and half sizes on the floor: fixed for walls, read for cubes (they move)."""
        if body in self.extent:
            return self.extent[body]
        pos = self.cube_position(self.names[body])
        half = self.scene.cube_size * 0.71  # any yaw
        return (float(pos[0]), float(pos[1]), half, half) if pos[2] > -1 else (1e9, 1e9, 0, 0)

    def in_bounds(self, x: float, y: float, radius: float) -> bool:
        """Whether a disc of `radius` metres at (x, y) lies within the bounds; 0 tests the point."""
        x0, x1, y0, y1 = self.scene.bounds
        return x0 + radius <= x <= x1 - radius and y0 + radius <= y <= y1 - radius

    def base_free(self, x: float, y: float, cubes: list[str], margin: float = 0.0) -> bool:
        """True when the robot's disc at (x, y) touches no wall and none of `cubes`."""
        if not self.in_bounds(x, y, self.scene.robot_radius):
            return False
        bodies = self.walls + [self.cubes[c] for c in cubes]
        return not self._hits(self.probe, (x, y, PROBE_Z), bodies, margin)

    def base_hits(self, x: float, y: float, cubes: list[str]) -> bool:
        """True when the robot's disc at (x, y) touches one of `cubes` (walls not checked)."""
        return self._hits(self.probe, (x, y, PROBE_Z), [self.cubes[c] for c in cubes], 0.0)

    def cube_fits(self, x: float, y: float, cubes: list[str], margin: float = 0.05) -> bool:
        """True when a cube put down at (x, y) would touch no wall and none of `cubes`."""
        if not self.in_bounds(x, y, self.scene.cube_size):
            return False
        bodies = self.walls + [self.cubes[c] for c in cubes]
        return not self._hits(self.cube_probe, (x, y, self.scene.cube_size / 2), bodies, margin)

    # --- pictures ------------------------------------------------------------------------

    def snapshot(self, width: int = 640, height: int = 400) -> tuple[int, int, bytes]:
        """An RGB picture from a camera that follows the robot (software renderer, headless).

        The camera keeps one direction (from the south-west, above) and follows the base's
        position, close enough that the arm and the fingers are plainly visible.
        """
        p = self.p
        x, y, _ = self.robot.pose
        for probe in (self.probe, self.cube_probe):  # collision probes would show as grey shapes
            p.resetBasePositionAndOrientation(probe, [0, 0, PARKED_Z], [0, 0, 0, 1],
                                              physicsClientId=self.client)
        return render(p, self.client, ([x - 0.95, y - 1.6, 1.45], [x + 0.3, y, 0.25]),
                      (55, 30.0), width, height)


def render(p: Any, client: int, camera: tuple[list[float], list[float]],
           lens: tuple[float, float], width: int, height: int) -> tuple[int, int, bytes]:
    """An RGBA picture with the software renderer (headless): `camera` is (eye, target),
    `lens` is (vertical field of view in degrees, far plane in metres)."""
    view = p.computeViewMatrix(camera[0], camera[1], [0, 0, 1], physicsClientId=client)
    proj = p.computeProjectionMatrixFOV(lens[0], width / height, 0.1, lens[1],
                                        physicsClientId=client)
    _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj,
                                        renderer=p.ER_TINY_RENDERER, physicsClientId=client)
    # A numpy array when pybullet was built with numpy, a flat tuple of ints otherwise.
    pixels = rgba.astype("uint8").tobytes() if hasattr(rgba, "astype") \
        else bytes(bytearray(int(v) for v in rgba))
    return width, height, pixels
