"""Small scenes and trees for the PyBullet world tests (imported by the test modules)."""

from __future__ import annotations

from pathlib import Path

from btplan.bt import Action, Condition, Fallback, Node, Sequence
from btplan.bt.decorators import Inverter
from btplan.lang import load
from btplan.model import Task

ROOT = Path(__file__).resolve().parents[3]
YOUBOT = ROOT / "domains" / "youbot.bt"
YOUBOT_SCENE = ROOT / "domains" / "scenes" / "youbot.toml"

OPEN_ROOM = """
[world]
bounds = [-1.0, 7.0, -2.0, 2.0]

[robot]
start = [0.0, 0.0, 0.0]

[[region]]
name = "goal"
min = [5.0, -0.5]
max = [6.0, 0.5]

[[cube]]
name = "green"
at = [2.0, 1.0]

[[cube]]
name = "blue"

[[cube]]
name = "red"

[[cube]]
name = "yellow"
"""


def youbot_task() -> Task:
    return load([str(YOUBOT)], None)


def write_scene(folder: Path, text: str = OPEN_ROOM, events: str = "") -> str:
    path = folder / "scene.toml"
    path.write_text(text + events, encoding="utf-8")
    return str(path)


def figure7_tree(to_green: str, to_goal: str) -> Node:
    """The paper's Figure 7 (Example 1) with the world's trajectories as arguments."""
    def move(target: str, traj: str) -> Node:
        return Fallback([Condition("near", (target,)),
                         Sequence([Inverter(Condition("blocks", ("_", traj))),
                                   Action("MoveTo", (target, traj))])])

    holding = Fallback([Condition("holding", ("green",)),
                        Sequence([Condition("hand_empty"), move("green", to_green),
                                  Action("Pick", ("green",))])])
    return Fallback([Condition("on", ("green", "goal")),
                     Sequence([holding, move("goal", to_goal), Action("Place", ("green", "goal"))])])
