"""The PyBullet world the tree ticks against: conditions, skills and refinement composed.

It sits on top of the backend: the scene state at the bottom, routes and samplers on it,
skills, conditions, refinement, agents and the recorder above those, and this class
composing them behind the World protocol. Conditions are measured on the scene every
time they are ticked; continuous parameters come through `refine`, which the planner
calls when it grounds an action template.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.errors import WorldError
from btplan.model import ActionTemplate, Parameter, Task
from btplan.robot.contract import Capabilities
from btplan.worlds.pybullet import motion, samplers
from btplan.worlds.pybullet.agents import SceneAgents
from btplan.worlds.pybullet.arm import Timings
from btplan.worlds.pybullet.conditions import Conditions, Key
from btplan.worlds.pybullet.refine import refine_values
from btplan.worlds.pybullet.routes import Routes
from btplan.worlds.pybullet.scene import Scene
from btplan.worlds.pybullet.skill_world import SkillWorld
from btplan.worlds.pybullet.skills import Scripted, Skill, move_to, pick, put_down
from btplan.worlds.pybullet.state import SceneState


class PyBulletWorld(SkillWorld[SceneState, Conditions]):
    """A mobile robot with a gripper among walls and cubes; see the module docstring."""

    def __init__(self, task: Task, scene: Scene, seed: int = 0, gui: bool = False,
                 verbose: bool = False, agents: SceneAgents | None = None) -> None:
        motion.set_log_level(verbose)
        motion.seed_rng(seed)
        self.scene = scene
        self.state = SceneState(task, scene, gui)
        self.routes = Routes(self.state)
        scene_names = {*self.state.cube_names, *(r.name for r in scene.regions)}
        # Initial facts about things the scene does not contain (a trajectory or pose the
        # problem declares) cannot be measured; they are kept as given.
        assumed = frozenset(a for a in task.initial_state
                            if any(x not in scene_names for x in a.args))
        super().__init__(task, self.state, Conditions(self.routes, assumed))
        self.timings = Timings()
        self.agents = agents if agents is not None else SceneAgents()
        self.agents.bind(self.state, self.check)
        self._refined: dict[tuple[str, str, tuple[tuple[str, str], ...]], list[str]] = {}

    def _skill(self, key: Key) -> Skill | None:
        name, args = key
        state, timings = self.state, self.timings

        def run(script: object) -> Skill:
            return Scripted(state, timings, script)  # type: ignore[arg-type]

        if name == "MoveTo" and len(args) == 2 and args[1] in state.trajectories:
            self.routes.refresh_pose(args[0])
            return run(move_to(self.routes, timings, args[0], args[1]))
        if name == "Pick" and len(args) == 1:
            return run(pick(state, timings, args[0]))
        if name == "Place" and len(args) == 2:
            self.routes.refresh_pose(args[1])
            spot = samplers.place_spot(state, args[1]) if state.is_near(args[1]) else None
            return run(put_down(state, timings, args[0], spot, args[1]))
        if name == "Drop" and len(args) == 1:
            return run(put_down(state, timings, args[0], samplers.drop_spot(state), None))
        if name in ("MoveTo", "Pick", "Place", "Drop"):
            return None
        raise WorldError(f"the PyBullet world has no skill for the action {name!r}")

    # --- refinement ----------------------------------------------------------------------

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """Values for a continuous parameter; the same question always gets the same answer."""
        memo = (template.name, parameter.name, tuple(sorted(binding.items())))
        if memo not in self._refined:
            self._refined[memo] = refine_values(self.routes, template, binding, parameter)
        return list(self._refined[memo])

    # --- lifecycle -----------------------------------------------------------------------

    def stats(self) -> dict[str, float]:
        """Simulated time and OMPL effort so far, for the run's closing note."""
        moves = sum(1 for a in self.started if a.name == "MoveTo")
        seconds = self.routes.plan_seconds
        total = sum(seconds)
        return {
            "sim_seconds": round(self.sim_seconds, 3),
            "action_ticks": self.action_ticks,
            "ompl_solves": len(seconds),
            "ompl_seconds_total": round(total, 4),
            "ompl_ms_per_solve": round(1000 * total / max(1, len(seconds)), 2),
            "ompl_ms_max": round(1000 * max(seconds, default=0.0), 2),
            "moves_started": moves,
            "poses_refined_again": self.routes.refreshed,
            "paths_joined": self.routes.joined,
            "paths_escaped": self.routes.escaped,
            "ompl_ms_per_move": round(1000 * total / max(1, moves), 2),
            "physics_steps": self.state.sim.steps,
            "physics_seconds": round(self.state.sim.physics_seconds, 3),
            "conditions_seconds": round(self.conditions.seconds, 3),
            "ik_seconds": round(self.timings.ik, 3),
            "arm_planning_seconds": round(self.timings.arm_planning, 3),
            "arm_ompl_solves": self.timings.ompl_solves,
            "arm_ompl_seconds": round(self.timings.ompl, 3),
            "arm_ompl_followed": self.timings.ompl_followed,
        }

    capabilities = Capabilities(refines=True, own_values=True, continuous=True,
                                outside_changes=True,
                                lessons=True, dead_ends=True, camera=True, closes=True)
    """Facts change while an action runs; agents push cubes while the robot acts; a
    failed grasp teaches a side not to try again; `dead_ends` and `close` are offered."""

    @property
    def outside_changes(self) -> int:
        """Physics steps in which the scene's agents pushed a cube (read by the loop)."""
        return self.state.sim.outside_changes

    @property
    def lessons(self) -> int:
        """Sides of a cube the arm failed to grasp from, and spots it failed to put a cube
        down at (read by the loop): after a new one the robot tries another side or spot,
        so a state seen before is not a loop yet."""
        state = self.state
        grasps = sum(len(poses) for _, poses in state.missed_from.values())
        return grasps + len(state.missed_drops)

    def dead_ends(self) -> list[str]:
        """Why the loop may be going round (read by its diagnosis): a cube the arm failed to
        grasp from every side the base can stand on, e.g. one pushed flush against a wall."""
        state, found = self.state, []
        for cube in state.missed_from:
            tried = state.missed_poses(cube)
            if tried and samplers.approach_pose(state, cube) is None \
                    and samplers.approach_pose(state, cube, avoid_cubes=False) is None:
                found.append(f"the arm found no grasp of {cube} from any of the {len(tried)} "
                             "sides the base can stand on")
        return found

    def scene_agents(self) -> list[SceneAgents]:
        """The scene's scripted external events, as one agent acting before each tick."""
        return [self.agents]
