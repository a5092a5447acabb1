"""The two-arm assembly world the tree ticks against: conditions, skills and agents composed.

The scene state is at the bottom (state.py on physics.py and panda.py), motions and
skills on it, conditions and the scene's agents beside them, and this class composes
them behind the same World protocol as the mobile robot's world. An action ends with
SUCCESS the moment all its effects are measured on the scene.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.errors import WorldError
from btplan.model import ActionTemplate, Parameter, Task
from btplan.robot.contract import Capabilities
from btplan.worlds.pybullet import motion
from btplan.worlds.pybullet.arm import Timings
from btplan.worlds.pybullet.assembly import skills
from btplan.worlds.pybullet.assembly.agents import AssemblyAgents, assembly_agents
from btplan.worlds.pybullet.assembly.conditions import AssemblyConditions, Key
from btplan.worlds.pybullet.assembly.scene import AssemblyScene
from btplan.worlds.pybullet.assembly.state import AssemblyState
from btplan.worlds.pybullet.sim import HZ
from btplan.worlds.pybullet.skill_world import SkillWorld


class AssemblyWorld(SkillWorld[AssemblyState, AssemblyConditions]):
    """Two Pandas across a table, parts to assemble on a fixture; see the module docstring."""

    capabilities = Capabilities(refines=True, camera=True, closes=True)

    def __init__(self, task: Task, scene: AssemblyScene, seed: int = 0, gui: bool = False,
                 verbose: bool = False) -> None:
        motion.set_log_level(verbose)
        motion.seed_rng(seed)
        self.scene = scene
        state = AssemblyState(task, scene, gui)
        super().__init__(task, state, AssemblyConditions(state, task))
        self.agents: AssemblyAgents = assembly_agents(self.state, self.check)
        self.timings = Timings()
        self.settle(1.0)  # parts laid out a millimetre above the table come to rest

    def settle(self, seconds: float) -> None:
        """Step the physics for `seconds` of simulated time with no skill running.

        At start-up, parts laid out a millimetre above the table come to rest.
        """
        for _ in range(int(seconds * HZ)):
            self.state.sim.step()

    def _skill(self, key: Key) -> skills.Scripted | None:
        script = self._script(key)
        if script is None:
            return None
        action = self.ground(key)

        def done() -> bool:
            return all(self.check((a.predicate, a.args)) for a in action.add) and not any(
                self.check((a.predicate, a.args)) for a in action.delete if a not in action.add)

        return skills.Scripted(self.state, script, done,
                               lambda: skills.let_go_unless_held(self.state))

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
        """Simulated time, physics steps and the arms' IK and planning effort so far.

        For the run's closing note; there is no base to plan for here.
        """
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
        """The scene's events, as one agent acting before each tick."""
        return [self.agents]
