"""Your own robot: the contract the acting loop drives, and a robot API on top of it.

`World` and `Capabilities` (btplan.robot.contract) are the low-level contract: five
calls keyed by `(name, args)`. `Robot` (btplan.robot.api) builds one from plain Python:
conditions as callables over the robot's state, actions as skills with poll / cancel,
or functions returning a `concurrent.futures.Future`. docs/robot.md has the whole
contract and a complete example. The robot API is imported on first use (PEP 562): the
built-in worlds need only the contract.
"""

from __future__ import annotations

import importlib

from btplan.robot.contract import Capabilities, Fact, Refining, World, capabilities_of

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.robot.api import Ask, Robot, action, condition, refiner
    from btplan.robot.skills import Skill

_HOMES = {"Ask": "api", "Robot": "api", "action": "api", "condition": "api", "refiner": "api",
          "Skill": "skills"}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'btplan.robot' has no attribute {name!r}")
    return getattr(importlib.import_module(f"btplan.robot.{home}"), name)


__all__ = ["Ask", "Capabilities", "Fact", "Refining", "Robot", "Skill", "World", "action",
           "capabilities_of", "condition", "refiner"]
