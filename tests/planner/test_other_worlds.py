"""The acting loop needs only the PlanningWorld protocol, as a simulator backend provides.

This world supplies its own trajectory values (like a motion planner would): names the
task never declared. The planner must accept them, ground MoveTo with them, and still
build the paper's tree.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.acting.loop import BlendedLoop
from btplan.bt import RUNNING, SUCCESS, LeafKey, Status
from btplan.lang import load
from btplan.model import ActionTemplate, Atom, Parameter, Task, instantiate
from tests.planner.shapes import DOMAINS, shape


class PlannedPaths:
    """A world whose trajectories are made up on request and are always collision free."""

    def __init__(self, task: Task) -> None:
        self.task = task
        self.state = {a for a in task.initial_state if a.predicate != "free"}
        self.paths: dict[str, str] = {}
        self.done: list[str] = []
        self._running: dict[LeafKey, int] = {}

    def facts(self) -> frozenset[Atom]:
        return frozenset(self.state | {Atom("free", (p,)) for p in self.paths})

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        target = binding.get("l", "somewhere")
        name = f"path_to_{target}"
        self.paths[name] = target
        return [name]

    def check(self, key: LeafKey) -> bool:
        return key in self.facts()

    def start(self, key: LeafKey) -> Status:
        self._running[key] = 2
        return RUNNING

    def step(self, key: LeafKey) -> Status:
        self._running[key] -= 1
        if self._running[key] > 0:
            return RUNNING
        del self._running[key]
        action = instantiate(self.task.domain.action_map[key[0]], key[1])
        self.state = set(action.apply(frozenset(self.state)))
        self.done.append(str(action))
        return SUCCESS

    def halt(self, key: LeafKey) -> None:
        self._running.pop(key, None)


def test_the_loop_works_with_values_the_world_makes_up() -> None:
    task = load([str(DOMAINS / "pick_place.bt")])
    world = PlannedPaths(task)
    loop = BlendedLoop(task, world)
    assert loop.run(200).reached
    assert world.done == ["MoveTo(cube, path_to_cube)", "Pick(cube)",
                          "MoveTo(goal, path_to_goal)", "Place(cube, goal)"]
    root = shape(loop.tree.root)
    assert root[2][1][2][1] == ("?", "near(cube)",
                                ("->", "free(path_to_cube)", "[MoveTo(cube, path_to_cube)]"))
