"""PyBullet backend: a mobile manipulator among cubes, MoveTo planned with OMPL.

Importing this package is cheap: pybullet, ompl and pillow are loaded only when a world
is opened (`open_world`), so the rest of btplan works without the simulation extra.
"""

from __future__ import annotations

import importlib
from pathlib import Path

from btplan import shipped
from btplan.errors import WorldError
from btplan.model import Task
from btplan.worlds.pybullet.assembly.world import AssemblyWorld
from btplan.worlds.pybullet.record import Recorder
from btplan.worlds.pybullet.world import PyBulletWorld

SCENES = shipped.scenes()
"""Where the scenes of the shipped domains live: package data, next to the domains."""


def default_scene(task: Task) -> Path:
    """The scene named after the domain, e.g. domains/scenes/youbot.toml for youbot."""
    return SCENES / f"{task.domain.name}.toml"


def open_world(task: Task, scene: str | None = None, seed: int = 0, gui: bool = False,
               record: str | None = None, verbose: bool = False
               ) -> PyBulletWorld | AssemblyWorld:
    """Build the PyBullet world of `task` from a scene file (by default the domain's own).

    Raises WorldError when the simulation extra is missing or the scene does not fit
    the problem, and InputError (located) when the scene file is malformed.
    """
    from btplan.worlds.pybullet.sim import quiet_stdout

    try:
        with quiet_stdout((1, 2)):
            for module in ("pybullet", "ompl", "PIL", *(("imageio_ffmpeg",) if record else ())):
                importlib.import_module(module)
    except ImportError as error:
        raise WorldError(f"the PyBullet backend needs the 'sim' extra ({error.name} is "
                         "missing): pip install 'btplan[sim]'") from None
    from btplan.worlds.pybullet.agents import scene_agents
    from btplan.worlds.pybullet.record import Recorder
    from btplan.worlds.pybullet.scene import load_scene
    from btplan.worlds.pybullet.world import PyBulletWorld

    recorder = Recorder(record) if record is not None else None  # refuse bad paths first
    path = Path(scene) if scene is not None else default_scene(task)
    if scene is None and not path.exists():
        raise WorldError(f"the PyBullet worlds have no scene for domain "
                         f"{task.domain.name!r}; they serve {_served()} (or a scene of "
                         "yours for them, with --scenario). For a robot of your own, see "
                         "docs/robot.md and run it with --world FILE.py:CLASS")
    from btplan.worlds.pybullet.assembly.scene import is_assembly_scene

    if is_assembly_scene(path):  # the two-arm scene of domains/yumi.bt
        return _open_assembly(task, path, seed, gui, recorder, verbose)
    _check_vocabulary(task)
    loaded = load_scene(path)
    arity = {p.name: p.arity for p in task.domain.predicates}
    agents = scene_agents(loaded.events, str(path), arity)
    world = PyBulletWorld(task, loaded, seed=seed, gui=gui, verbose=verbose, agents=agents)
    if recorder is not None:
        world.on_frame = recorder
        world.save_recording = recorder.save
    return world


MOBILE_PREDICATES = frozenset({"near", "holding", "hand_empty", "on", "blocks", "route"})
MOBILE_ACTIONS = frozenset({"MoveTo", "Pick", "Place", "Drop"})
"""What the mobile manipulator's world can measure and do (conditions.py, world.py)."""


def _served() -> str:
    scenes = sorted(p.stem for p in SCENES.glob("*.toml"))
    domains = [s for s in scenes if (SCENES.parent / f"{s}.bt").exists()]
    return (f"the shipped domains {', '.join(d + '.bt' for d in domains)} (scenes: "
            f"{', '.join(scenes)})")


def _check_vocabulary(task: Task) -> None:
    """Refuse, before anything starts, a domain the mobile manipulator cannot act in."""
    unknown = sorted({p.name for p in task.domain.predicates} - MOBILE_PREDICATES)
    actions = sorted({a.name for a in task.domain.actions} - MOBILE_ACTIONS)
    if unknown or actions:
        what = "; ".join(part for part in (
            f"predicates it cannot measure: {', '.join(unknown)}" if unknown else "",
            f"actions it has no skill for: {', '.join(actions)}" if actions else "") if part)
        raise WorldError(f"the PyBullet world cannot act in domain {task.domain.name!r} "
                         f"({what}); it serves {_served()}. For a robot of your own, see "
                         "docs/robot.md and run it with --world FILE.py:CLASS")


def _open_assembly(task: Task, path: Path, seed: int, gui: bool, recorder: Recorder | None,
                   verbose: bool) -> AssemblyWorld:
    from btplan.worlds.pybullet.assembly.scene import load_assembly_scene

    world = AssemblyWorld(task, load_assembly_scene(path), seed=seed, gui=gui, verbose=verbose)
    if recorder is not None:
        world.on_frame = recorder
        world.save_recording = recorder.save
    return world


__all__ = ["AssemblyWorld", "PyBulletWorld", "default_scene", "open_world"]
