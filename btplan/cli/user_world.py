"""`btplan run --world FILE.py:CLASS`: the user's own robot, loaded and checked before tick 1.

The class (or any callable) is found in a Python file or an importable module and
called with the task when it takes an argument, without one otherwise. What it returns
must have the five calls of btplan.robot.World (a `btplan.robot.Robot` is checked
against the task when the run starts, as `btplan.run` checks every robot). Every
failure is bad input: exit 2, naming the flag and what is wrong.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

from btplan.errors import BtplanError, InputError, Span
from btplan.model import Task

AT = Span("--world", 1, 1)
CALLS = ("check", "start", "step", "halt", "facts")


def open_user_world(spec: str, task: Task) -> Any:
    """The world `spec` names (`path/to/file.py:Name` or `package.module:Name`), made for `task`."""
    where, sep, name = spec.rpartition(":")
    if not sep or not where or not name.isidentifier():
        raise InputError(f"expected FILE.py:CLASS or MODULE:CLASS, got {spec!r}", AT)
    module = _module(where)
    factory = getattr(module, name, None)
    if factory is None or not callable(factory):
        from difflib import get_close_matches

        names = sorted(n for n, v in vars(module).items()
                       if callable(v) and not n.startswith("_"))
        near = get_close_matches(name, names, n=1)
        raise InputError(f"{where} has no class or function named {name!r}", AT,
                         f"did you mean '{near[0]}'?" if near else None)
    try:
        world = factory(task) if _takes_an_argument(factory) else factory()
    except BtplanError:
        raise
    except Exception as error:  # noqa: BLE001 (the user's constructor: report, no traceback)
        raise InputError(f"{spec} raised while starting: {type(error).__name__}: {error}",
                         AT) from None
    missing = [c for c in CALLS if not callable(getattr(world, c, None))]
    if missing:
        raise InputError(f"{spec} made a {type(world).__name__}, which lacks "
                         f"{', '.join(missing)} of the world contract", AT,
                         "see docs/robot.md")
    return world


def _module(where: str) -> ModuleType:
    if where.endswith(".py") or "/" in where or Path(where).suffix == ".py":
        path = Path(where)
        if not path.is_file():
            raise InputError(f"no such file: {where}", AT)
        name = f"btplan_user_world_{abs(hash(str(path.resolve())))}"
        loader = importlib.util.spec_from_file_location(name, path)
        if loader is None or loader.loader is None:
            raise InputError(f"cannot load {where} as Python", AT)
        module = importlib.util.module_from_spec(loader)
        sys.modules[name] = module
        sys.path.insert(0, str(path.resolve().parent))  # its own helper modules import
        try:
            loader.loader.exec_module(module)
        except Exception as error:  # noqa: BLE001 (the user's file: report, no traceback)
            raise InputError(f"{where} failed to import: {type(error).__name__}: {error}",
                             AT) from None
        finally:
            sys.path.remove(str(path.resolve().parent))
        return module
    try:
        return importlib.import_module(where)
    except Exception as error:  # noqa: BLE001
        raise InputError(f"cannot import {where}: {type(error).__name__}: {error}", AT) from None


def _takes_an_argument(factory: Any) -> bool:
    try:
        parameters = list(inspect.signature(factory).parameters.values())
    except (TypeError, ValueError):
        return True
    required = [p for p in parameters
                if p.default is p.empty and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return bool(required) or any(p.kind is p.VAR_POSITIONAL for p in parameters)
