"""Backchaining from goal conditions to a reactive BT: the paper's Algorithms 1-3."""

from btplan.planner.achievers import AchieverIndex
from btplan.planner.conflicts import Conflict, Judge, find_conflicts, placement_conflicts
from btplan.planner.expand import (
    atomic_bt,
    condition_node,
    expand_tree,
    failed_conditions,
    get_condition_to_expand,
    initial_tree,
    literal_of,
)
from btplan.classical import Mutexes
from btplan.planner.options import PlannerOptions
from btplan.planner.priority import Resolution, increase_priority, resolve_conflicts
from btplan.planner.protocol import PlanningWorld, Refiner

__all__ = [
    "AchieverIndex", "Conflict", "Judge", "Mutexes", "PlannerOptions", "PlanningWorld", "Refiner", "Resolution",
    "atomic_bt", "condition_node", "expand_tree", "failed_conditions", "find_conflicts",
    "get_condition_to_expand", "increase_priority", "initial_tree", "literal_of",
    "placement_conflicts", "resolve_conflicts",
]
