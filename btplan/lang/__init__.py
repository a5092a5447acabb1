"""Read domains and problems (the .bt language and PDDL) into checked models.

The readers build their parsers from the grammars (lark) when first imported; the
names below are imported on first use (PEP 562), so that a submodule that needs no
parser (the problem generators, the writers) can be imported without them.
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.lang.loader import (
        BtFile,
        Collection,
        collect,
        load,
        load_domain,
        load_problem,
        parse_bt,
        with_goal,
    )
    from btplan.lang.report import InputErrors

_HOMES = {"BtFile": "loader", "Collection": "loader", "collect": "loader", "load": "loader",
          "load_domain": "loader", "load_problem": "loader", "parse_bt": "loader",
          "with_goal": "loader", "InputErrors": "report"}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'btplan.lang' has no attribute {name!r}")
    return getattr(importlib.import_module(f"btplan.lang.{home}"), name)


__all__ = [
    "BtFile",
    "Collection",
    "InputErrors",
    "collect",
    "load",
    "load_domain",
    "load_problem",
    "parse_bt",
    "with_goal",
]
