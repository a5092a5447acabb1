"""Behavior Tree nodes, the tick engine and the formats trees are saved in."""

from btplan.bt.blackboard import Blackboard, NodeError
from btplan.bt.composites import Fallback, Sequence
from btplan.bt.debug import LeafContractError, StrictWorld
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
from btplan.bt.parallel import Parallel
from btplan.bt.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from btplan.bt.trace import (
    NodeTick,
    TickRecorder,
    TickTrace,
    node_ids,
    traces_to_jsonl,
    write_jsonl,
)
from btplan.bt.tree import BehaviorTree
from btplan.bt.world import LeafKey, World

__all__ = [
    "FAILURE", "IDLE", "RUNNING", "SKIPPED", "SUCCESS", "Action", "BehaviorTree", "Blackboard",
    "Composite", "Condition", "Decorator", "Fallback", "ForceFailure", "ForceSuccess",
    "Inverter", "Leaf", "LeafContractError", "LeafKey", "Node", "NodeError", "NodeTick",
    "Parallel", "Retry", "Sequence", "Status", "StrictWorld", "TickRecorder", "TickTrace",
    "Timeout", "World", "node_ids", "traces_to_jsonl", "write_jsonl",
]
