"""The two-arm assembly world the tree ticks against: conditions, skills and agents composed.

The scene state is at the bottom (state.py on physics.py and panda.py), motions and
skills on it, conditions and the scene's agents beside them, and this class composes
them behind the same World protocol as the mobile robot's world. An action ends with
SUCCESS the moment all its effects are measured on the scene.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from btplan.bt.status import FAILURE, RUNNING, Status
from btplan.errors import WorldError
from btplan.model import ActionTemplate, Atom, GroundAction, Parameter, Task, instantiate
from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.arm import Timings
from btplan.worlds.pybullet.assembly import skills
from btplan.worlds.pybullet.assembly.agents import AssemblyAgents, assembly_agents
from btplan.worlds.pybullet.assembly.conditions import AssemblyConditions, Key
from btplan.worlds.pybullet.assembly.scene import AssemblyScene
from btplan.worlds.pybullet.assembly.state import AssemblyState
from btplan.worlds.pybullet.sim import HZ

Frame = Callable[[AssemblyState, str], None]


class AssemblyWorld:
    """Two Pandas across a table, parts to assemble on a fixture; see the module docstring."""

    def __init__(self, task: Task, scene: AssemblyScene, seed: int = 0, gui: bool = False,
                 verbose: bool = False) -> None:
        motion.set_log_level(verbose)
        motion.seed_rng(seed + 1)  # OMPL refuses a zero seed
        self.task, self.scene = task, scene
        self.state = AssemblyState(task, scene, gui)
        self.conditions = AssemblyConditions(self.state, task)
        self.agents: AssemblyAgents = assembly_agents(self.state, self.check)
        self.timings = Timings()
        self.running: dict[Key, skills.Scripted] = {}
        self.executed: list[GroundAction] = []
        self.started: list[GroundAction] = []
        self.halted: list[GroundAction] = []
        self.failed: list[GroundAction] = []
        self.on_frame: Frame | None = None
        self.save_recording: Callable[[], None] | None = None
        self.action_ticks = 0
        self.current = ""
        self.settle(1.0)  # parts laid out a millimetre above the table come to rest

    def settle(self, seconds: float) -> None:
        for _ in range(int(seconds * HZ)):
            self.state.sim.step()

    @property
    def sim_seconds(self) -> float:
        return self.state.seconds

    # --- conditions ----------------------------------------------------------------------

    def check(self, key: Key) -> bool:
        return self.conditions.check(key)

    def facts(self) -> frozenset[Atom]:
        return self.conditions.facts()

    # --- actions -------------------------------------------------------------------------

    def ground(self, key: Key) -> GroundAction:
        template = self.task.domain.action_map.get(key[0])
        if template is None or len(template.parameters) != len(key[1]):
            raise WorldError(f"{key[0]}{key[1]} is not an action of domain "
                             f"{self.task.domain.name!r}")
        return instantiate(template, key[1])

    def start(self, key: Key) -> Status:
        action = self.ground(key)
        self.started.append(action)
        script = self._script(key)
        if script is None:
            self.failed.append(action)
            return FAILURE

        def done() -> bool:
            return all(self.check((a.predicate, a.args)) for a in action.add) and not any(
                self.check((a.predicate, a.args)) for a in action.delete if a not in action.add)

        self.running[key] = skills.Scripted(self.state, script, done,
                                            lambda: skills.let_go_unless_held(self.state))
        return self.step(key)

    def step(self, key: Key) -> Status:
        skill = self.running.get(key)
        if skill is None:
            return FAILURE
        self.action_ticks += 1
        status = skill.step()
        self.current = str(self.ground(key))
        if status is not RUNNING:
            del self.running[key]
            (self.failed if status is FAILURE else self.executed).append(self.ground(key))
        if self.on_frame is not None:
            self.on_frame(self.state, f"t={self.sim_seconds:5.1f}s  {self.current}")
        return status

    def halt(self, key: Key) -> None:
        skill = self.running.pop(key, None)
        if skill is not None:
            self.halted.append(self.ground(key))
            skill.halt()

    def _script(self, key: Key) -> skills.Script | None:
        name, args = key
        state, timings = self.state, self.timings
        if name == "Pick" and len(args) == 5:
            return skills.pick(state, timings, args[0], args[1])
        if name == "Place" and len(args) == 5:
            return skills.place(state, timings, args[0], args[1], args[2])
        if name == "Handover" and len(args) == 5:
            return skills.handover(state, timings, args[0], args[1], args[2])
        if name == "Insert" and len(args) == 4:
            return skills.insert(state, timings, args[0], args[1])
        raise WorldError(f"the assembly world has no skill for the action {name}{args}")

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """No continuous parameters here: every value is an object of the problem."""
        return []

    # --- lifecycle -----------------------------------------------------------------------

    def stats(self) -> dict[str, float]:
        return {
            "sim_seconds": round(self.sim_seconds, 3),
            "action_ticks": self.action_ticks,
            "physics_steps": self.state.sim.steps,
            "physics_seconds": round(self.state.sim.physics_seconds, 3),
            "ik_seconds": round(self.timings.ik, 3),
            "arm_planning_seconds": round(self.timings.arm_planning, 3),
            "arm_ompl_solves": self.timings.ompl_solves,
            "arm_ompl_seconds": round(self.timings.ompl, 3),
        }

    def scene_agents(self) -> list[AssemblyAgents]:
        return [self.agents]

    def halt_all(self) -> None:
        for key in sorted(self.running):
            self.halt(key)

    def close(self) -> None:
        self.halt_all()
        if self.save_recording is not None:
            self.save_recording()
            self.save_recording = None
        self.state.close()
        motion.release()
