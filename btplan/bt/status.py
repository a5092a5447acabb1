"""The statuses a node returns when ticked, named as in BehaviorTree.CPP."""

from __future__ import annotations

from enum import Enum


class Status(Enum):
    """SUCCESS, FAILURE and RUNNING as in the paper; IDLE means not ticked (yet).

    SKIPPED is BehaviorTree.CPP 4's answer of a node whose `_skipIf` held (or whose
    `_while` did not): its parent moves on as if the node were not there. Only trees
    read from BT.CPP XML produce it.
    """

    IDLE = "IDLE"
    SUCCESS = "SUCCESS"
    FAILURE = "FAILURE"
    RUNNING = "RUNNING"
    SKIPPED = "SKIPPED"


SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE
RUNNING = Status.RUNNING
IDLE = Status.IDLE
SKIPPED = Status.SKIPPED
