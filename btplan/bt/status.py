"""The statuses a node returns when ticked, named as in BehaviorTree.CPP."""

from __future__ import annotations

from enum import Enum


class Status(Enum):
    """SUCCESS, FAILURE and RUNNING as in the paper; IDLE means not ticked (yet)."""

    IDLE = "IDLE"
    SUCCESS = "SUCCESS"
    FAILURE = "FAILURE"
    RUNNING = "RUNNING"


SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE
RUNNING = Status.RUNNING
IDLE = Status.IDLE
