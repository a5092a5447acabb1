"""RefineActions (Algorithm 1, line 5): continuous values the planner asks the world for.

Trajectories are planned with OMPL; a place for a cube that the condition being achieved
does not fix (an obstacle to put aside) is sampled off every known path and clear of the
other cubes, so that the subtree the planner builds with it conflicts with no route.
Values are named once and refreshed behind their name when they go stale (routes.py).
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.model import ActionTemplate, Literal, Parameter
from btplan.worlds.pybullet.routes import Routes


def refine_values(routes: Routes, template: ActionTemplate, binding: Mapping[str, str],
                  parameter: Parameter) -> list[str]:
    """Trajectories are planned to the bound location; places are sampled poses."""
    domain = routes.state.task.domain
    if domain.is_subtype(parameter.type, "trajectory"):
        related = [lit for lit in template.constraints if parameter.name in lit.args]
        target = _target_of(template, binding, parameter, related)
        return [routes.new_trajectory(target)] if target is not None else []
    if "pose" in domain.type_parents and domain.is_subtype("pose", parameter.type):
        pose = routes.sample_pose()
        return [pose] if pose is not None else []
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
