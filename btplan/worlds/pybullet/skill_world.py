"""What both PyBullet worlds do alike: run one skill per action leaf, keep the logs.

The mobile robot and the two-arm assembly differ in their scene, conditions and
skills, not in how a leaf's start, step and halt drive a skill, nor in the logs of
grounded actions every world keeps (traces, --plan-out, agents). Each world builds its
state and conditions, calls `SkillWorld.__init__`, and says which skill runs an action
(`_skill`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, Protocol, TypeVar

from btplan.bt.status import FAILURE, RUNNING, Status
from btplan.errors import WorldError
from btplan.model import Atom, GroundAction, Task, instantiate
from btplan.worlds.logs import RecentLog
from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.record import Camera
from btplan.worlds.pybullet.skills import Skill

Key = tuple[str, tuple[str, ...]]


class _State(Protocol):
    @property
    def seconds(self) -> float: ...

    @property
    def sim(self) -> Camera: ...

    def close(self) -> None: ...


class _Conditions(Protocol):
    def check(self, key: Key) -> bool: ...

    def facts(self) -> frozenset[Atom]: ...


StateT = TypeVar("StateT", bound=_State)
ConditionsT = TypeVar("ConditionsT", bound=_Conditions)


class SkillWorld(Generic[StateT, ConditionsT]):
    """Start, step and halt skills for the tree's action leaves; see the module docstring."""

    def __init__(self, task: Task, state: StateT, conditions: ConditionsT) -> None:
        self.task = task
        self.state = state
        self.conditions = conditions
        self.running: dict[Key, Skill] = {}
        self.executed: list[GroundAction] = []
        self.started: RecentLog[GroundAction] = RecentLog()
        self.halted: RecentLog[GroundAction] = RecentLog()
        self.failed: RecentLog[GroundAction] = RecentLog()
        self.reasons: list[tuple[GroundAction, str]] = []
        """Each failed action with the reason its skill gave for it ('' for none)."""
        self.on_frame: Callable[[StateT, str], None] | None = None
        self.save_recording: Callable[[], None] | None = None
        self.action_ticks = 0
        self.current = ""

    def _skill(self, key: Key) -> Skill | None:
        """The skill that runs the action, or None when it cannot start here."""
        raise NotImplementedError

    @property
    def sim_seconds(self) -> float:
        """Simulated time: the physics steps taken so far."""
        return self.state.seconds

    # --- conditions ----------------------------------------------------------------------

    def check(self, key: Key) -> bool:
        """Asked of this world's conditions, which measure the scene now and keep no state."""
        return self.conditions.check(key)

    def facts(self) -> frozenset[Atom]:
        """The whole state as the planner sees it, measured by this world's conditions."""
        return self.conditions.facts()

    # --- actions -------------------------------------------------------------------------

    def running_actions(self) -> list[GroundAction]:
        """The actions whose skills run now, oldest first (for the `help` agent)."""
        return [self.ground(key) for key in self.running]

    def ground(self, key: Key) -> GroundAction:
        """The grounded action of a leaf key, for the logs."""
        template = self.task.domain.action_map.get(key[0])
        if template is None or len(template.parameters) != len(key[1]):
            raise WorldError(f"{key[0]}{key[1]} is not an action of domain "
                             f"{self.task.domain.name!r}")
        return instantiate(template, key[1])

    def start(self, key: Key) -> Status:
        """Log the action as started and run its skill's first tick at once.

        FAILURE, with the reason "it cannot start here", when the world has no skill that can
        begin it now (a trajectory it does not know, say).
        """
        action = self.ground(key)
        self.started.append(action)
        skill = self._skill(key)
        if skill is None:
            self.failed.append(action)
            self.reasons.append((action, "it cannot start here"))
            return FAILURE
        self.running[key] = skill
        return self.step(key)

    def step(self, key: Key) -> Status:
        """Run one tick of the action's skill; FAILURE when none runs for it (halted or ended).

        An outcome is logged (a failure with its reason), and the recorder gets a labelled frame.
        """
        skill = self.running.get(key)
        if skill is None:
            return FAILURE
        self.action_ticks += 1
        status = skill.step()
        self.current = f"{key[0]}({', '.join(key[1])})"
        if status is not RUNNING:
            del self.running[key]
            action = self.ground(key)
            (self.failed if status is FAILURE else self.executed).append(action)
            if status is FAILURE:
                self.reasons.append((action, skill.reason))
        if self.on_frame is not None:
            self.on_frame(self.state, f"t={self.sim_seconds:5.1f}s  {self.current}")
        return status

    def halt(self, key: Key) -> None:
        """Stop the action's skill, which leaves the robot safe; a key not running is ignored."""
        skill = self.running.pop(key, None)
        if skill is not None:
            self.halted.append(self.ground(key))
            skill.halt()

    def camera_png(self, width: int = 320, height: int = 200) -> bytes:
        """A PNG picture of the robot now, labelled with the sim time and the action
        (what `btplan run --view` shows beside each tick)."""
        import io

        from btplan.worlds.pybullet.record import frame

        image = frame(self.state, f"t={self.sim_seconds:5.1f}s  {self.current}", width, height)
        buffer = io.BytesIO()
        image.save(buffer, format="PNG", optimize=False, compress_level=1)
        return buffer.getvalue()

    # --- lifecycle -----------------------------------------------------------------------

    def halt_all(self) -> None:
        """Halt every running skill (an interrupted run): each leaves the world consistent."""
        for key in sorted(self.running):
            self.halt(key)

    def close(self) -> None:
        """Halt what runs, save the recording (if any) and disconnect from PyBullet."""
        self.halt_all()
        if self.save_recording is not None:
            self.save_recording()
            self.save_recording = None
        self.state.close()
        motion.release()
