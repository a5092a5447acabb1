"""RefineActions (Algorithm 1, line 5): continuous values the planner asks the world for.

Trajectories are planned with OMPL, poses sampled off the path to clear, and the cubes
that block a trajectory read off the scene.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.model import ActionTemplate, Literal, Parameter
from btplan.worlds.pybullet.routes import Routes


def refine_values(routes: Routes, template: ActionTemplate, binding: Mapping[str, str],
                  parameter: Parameter) -> list[str]:
    """Trajectories are planned, poses sampled off the path, blockers read off the path."""
    world = routes.state
    domain = world.task.domain
    related = [lit for lit in template.constraints if parameter.name in lit.args]
    if domain.is_subtype(parameter.type, "trajectory"):
        target = _target_of(template, binding, parameter, related)
        return [routes.new_trajectory(target)] if target is not None else []
    traj_name = next((v for _, v in sorted(binding.items()) if v in world.trajectories), None)
    if domain.is_subtype(parameter.type, "pose"):
        pose = routes.sample_pose(world.trajectories.get(traj_name) if traj_name else None)
        return [pose] if pose is not None else []
    if traj_name is not None:
        traj = world.trajectories[traj_name]
        routes.prepare(traj_name)
        found = sorted(c for c in world.blockers(traj) if c in world.sim.cubes)
        allowed = set(world.task.objects_of(parameter.type))
        found = [c for c in found if c in allowed]
        traj.clearing.update(found)
        return found
    return []


def _target_of(template: ActionTemplate, binding: Mapping[str, str], parameter: Parameter,
               related: list[Literal]) -> str | None:
    """The location a trajectory leads to: named with it in a `where`, else the first bound."""
    for lit in related:
        for arg in lit.args:
            if arg != parameter.name and arg in binding:
                return binding[arg]
    bound = [binding[p.name] for p in template.parameters if p.name in binding]
    return bound[0] if bound else None
