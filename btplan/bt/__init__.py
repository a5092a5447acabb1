"""Behavior Tree nodes, the tick engine and the formats trees are saved in.

`StrictWorld`, `LeafContractError` (btplan/bt/debug.py, for `--debug`), `Parallel`, the
blackboard's names (BT.CPP trees) and the per-tick traces' (`--trace`) are imported on
first use (PEP 562): trees grown by backchaining need none of them, and a plan run
imports what it uses.
"""

from __future__ import annotations

import importlib

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import (
    Decorator,
    ForceFailure,
    ForceSuccess,
    Inverter,
    Retry,
    Timeout,
)
from btplan.bt.leaves import Action, Condition, Leaf
from btplan.bt.node import Composite, Node
from btplan.bt.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.tree import BehaviorTree
from btplan.bt.world import LeafKey, World

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

    from btplan.bt.blackboard import Blackboard, NodeError
    from btplan.bt.debug import LeafContractError, StrictWorld
    from btplan.bt.parallel import Parallel
    from btplan.bt.trace import (
        NodeTick,
        TickRecorder,
        TickTrace,
        node_ids,
        traces_to_jsonl,
        write_jsonl,
    )

_HOMES = {"LeafContractError": "debug", "StrictWorld": "debug", "Parallel": "parallel",
          "Blackboard": "blackboard", "NodeError": "blackboard", "NodeTick": "trace",
          "TickRecorder": "trace", "TickTrace": "trace", "node_ids": "trace",
          "traces_to_jsonl": "trace", "write_jsonl": "trace"}


def __getattr__(name: str) -> Any:
    home = _HOMES.get(name)
    if home is None:
        raise AttributeError(f"module 'btplan.bt' has no attribute {name!r}")
    return getattr(importlib.import_module(f"btplan.bt.{home}"), name)

__all__ = [
    "FAILURE", "IDLE", "RUNNING", "SKIPPED", "SUCCESS", "Action", "BehaviorTree", "Blackboard",
    "Composite", "Condition", "Decorator", "Fallback", "ForceFailure", "ForceSuccess",
    "Inverter", "Leaf", "LeafContractError", "LeafKey", "Node", "NodeError", "NodeTick",
    "Parallel", "Retry", "Sequence", "Status", "StrictWorld", "TickRecorder", "TickTrace",
    "Timeout", "World", "node_ids", "traces_to_jsonl", "write_jsonl",
]
