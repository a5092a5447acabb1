"""Named disturbance scenarios for sweeps: which agents act, at what rate, for how long.

A scenario turns a rate into the agents of one seeded run, so that every method of one
seed faces the same agents. It is a built-in name, a file of disturbance specs in
which `{p}` stands for the rate, or `module:attribute` naming a Scenario (how a user,
or a test, brings agents of their own; the module must be importable by the workers).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from difflib import get_close_matches
from pathlib import Path

from btplan.errors import InputError, Span
from btplan.model import Task
from btplan.worlds.agents import Agent, agents_from_specs, check_world
from btplan.worlds.disturb import DisturbSpec, check_specs, parse_spec
from btplan.worlds.meddlers import BlockPath, MovePackage, ToppleTower

Meddlers = Callable[[Task, float, int], list[Agent]]


def _no_meddlers(task: Task, rate: float, seed: int) -> list[Agent]:
    return []


@dataclass(frozen=True)
class Scenario:
    """Agents as a function of (task, rate, seed); the same call gives the same agents.

    `specs` are disturbance specs with `{p}` for the rate (left out at rate 0);
    `meddlers` builds agents that specs cannot express. `min_duration` stretches
    shorter actions: an action of one tick finishes as it starts, so a whole plan
    could run within one tick, out of any agent's reach. `max_ticks` is the budget.
    """

    name: str
    description: str
    specs: tuple[str, ...] = ()
    meddlers: Meddlers = field(default=_no_meddlers)
    min_duration: int = 1
    max_ticks: int = 400
    sims: tuple[str, ...] = ("symbolic",)
    """The worlds its agents can act in (`meddlers` set symbolic facts)."""

    def prepare(self, task: Task) -> Task:
        """The task as this scenario runs it (actions stretched to `min_duration`)."""
        if all(a.duration >= self.min_duration for a in task.domain.actions):
            return task
        slow = tuple(a.model_copy(update={"duration": max(a.duration, self.min_duration)})
                     for a in task.domain.actions)
        return Task(domain=task.domain.model_copy(update={"actions": slow}), problem=task.problem)

    def disturb_specs(self, rate: float) -> list[DisturbSpec]:
        """The scenario's specs with `{p}` set to `rate`; none at rate 0, so a rate-0 run is the
        undisturbed baseline."""
        if rate <= 0:
            return []
        return [parse_spec(s.format(p=f"{rate:g}"), Span(f"scenario {self.name}", 1, 1))
                for s in self.specs]

    def check(self, task: Task) -> None:
        """Refuse, before any run, specs naming actions, predicates or objects `task` lacks; read
        at rate 0.5, since at rate 0 no spec is made."""
        check_specs(self.disturb_specs(0.5), task)

    def check_sim(self, sim: str) -> None:
        """Refuse, before any run, a scenario whose agents the `sim` world cannot serve."""
        if sim not in self.sims:
            raise InputError(f"the scenario '{self.name}' runs in the "
                             f"{' or '.join(self.sims)} world only", Span("--scenario", 1, 1),
                             "with --sim pybullet use --scenario scene or shove, or a spec "
                             "file of disturbances the simulator can carry out")

    def agents_in(self, world: object, sim: str, task: Task, rate: float,
                  seed: int) -> list[Agent]:
        """`agents`, once `world` is known to carry out every spec (a located error if not)."""
        check_world(self.disturb_specs(rate), world, f"the {sim} world")
        return self.agents(task, rate, seed)

    def agents(self, task: Task, rate: float, seed: int) -> list[Agent]:
        """Spec agents first, then the others: the order they act in every tick."""
        specs = agents_from_specs(self.disturb_specs(rate), seed)
        return [*specs, *(self.meddlers(task, rate, seed) if rate > 0 else [])]


def _obstacle(task: Task, rate: float, seed: int) -> list[Agent]:
    return [BlockPath(rate, seed)]


def _towers(task: Task, rate: float, seed: int) -> list[Agent]:
    return [ToppleTower(rate, seed)]


def _packages(task: Task, rate: float, seed: int) -> list[Agent]:
    return [MovePackage(rate, seed, task.objects_of("package"))]


def _shove(task: Task, rate: float, seed: int) -> list[Agent]:
    from btplan.worlds.pybullet.agents import Shove

    return [Shove(rate, seed)]


BUILTIN: dict[str, Scenario] = {s.name: s for s in (
    Scenario("undo", "the robot's last action is undone at rate p", ("undo@p={p}",)),
    Scenario("obstacle", "Example 2: undo at rate p, and the sphere rolls onto the free "
             "path to the goal at rate p", ("undo@p={p}",), _obstacle),
    Scenario("towers", "blocksworld: the top block of a tower is put on the table at rate p",
             meddlers=_towers, min_duration=2),
    Scenario("packages", "logistics: a package on the ground is carried to another place of "
             "its city at rate p", meddlers=_packages, min_duration=2),
    Scenario("scene", "the simulator scene's own events (PyBullet); the rate is only recorded",
             max_ticks=3000, sims=("symbolic", "pybullet")),
    Scenario("shove", "PyBullet: the scene's own events, and a pusher pushes a cube the robot "
             "does not hold to a random free spot of the floor at rate p",
             meddlers=_shove, max_ticks=3000, sims=("pybullet",)),
)}


def resolve(name: str) -> Scenario:
    """A built-in scenario, a spec file with `{p}`, or `module:attribute`."""
    if name in BUILTIN:
        return BUILTIN[name]
    path = Path(name)
    if path.is_file():
        return _from_file(path)
    if ":" in name and not path.suffix:
        module, _, attribute = name.partition(":")
        try:
            found = getattr(importlib.import_module(module), attribute)
        except (ImportError, AttributeError) as error:
            raise InputError(f"cannot load scenario '{name}' ({error})",
                             Span("--scenario", 1, 1)) from None
        if not isinstance(found, Scenario):
            raise InputError(f"'{name}' is not a Scenario", Span("--scenario", 1, 1))
        return found
    near = get_close_matches(name, sorted(BUILTIN), n=1)
    raise InputError(f"unknown scenario '{name}'", Span("--scenario", 1, 1),
                     f"did you mean '{near[0]}'?" if near
                     else "one of " + ", ".join(sorted(BUILTIN)) + ", or a spec file")


def _from_file(path: Path) -> Scenario:
    specs: list[str] = []
    for line in path.read_text(encoding="utf-8").splitlines():
        body = line.split("#", 1)[0].strip()
        if body:
            specs.append(body)
    scenario = Scenario(path.stem, f"specs of {path.name}", tuple(specs),
                        sims=("symbolic", "pybullet"))
    scenario.disturb_specs(0.5)  # a malformed spec is refused before any run
    return scenario
