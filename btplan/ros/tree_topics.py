"""The growing tree on ROS 2 topics, for ros2 bag and other nodes.

- `NS/tree` (std_msgs/String, kept for late subscribers): the tree as BehaviorTree.CPP
  XML with a `_uid` on every node (btplan.monitor.tree_state), whenever it changes;
- `NS/statuses` (std_msgs/String, the last KEPT_TICKS kept for late subscribers): one
  JSON object per tick,
  `{"tick": N, "status": ..., "statuses": [[uid, status], ...], "grew": [...]}`.
"""

from __future__ import annotations

import json
from typing import Any

from btplan.monitor.tree_state import TreeState

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.monitor.run_monitor import TickUpdate

__all__ = ["CLOSE_WAIT", "KEPT_TICKS", "TreeTopics"]

CLOSE_WAIT = 1.0
"""Seconds the end of a run waits for subscribers to acknowledge the last messages."""

KEPT_TICKS = 100
"""Ticks of statuses kept for a subscriber that comes late (and asks for them, with a
transient-local subscription): one that joins while the run goes on gets the ticks it
missed just before."""


class TreeTopics:
    """A run's monitor that publishes on the robot's node (module docstring)."""

    def __init__(self, node: Any, namespace: str) -> None:
        from rclpy.qos import DurabilityPolicy, QoSProfile
        from std_msgs.msg import String

        self._string = String
        kept = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        recent = QoSProfile(depth=KEPT_TICKS, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        base = namespace.rstrip("/")
        self.tree = node.create_publisher(String, f"{base}/tree", kept)
        self.statuses = node.create_publisher(String, f"{base}/statuses", recent)
        self._version = -1

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        """The tree when it changed, and the tick's statuses."""
        if state.versions != self._version:
            self._version = state.versions
            self.tree.publish(self._string(data=state.xml))
        record = update.record
        self.statuses.publish(self._string(data=json.dumps({
            "tick": record.tick, "status": record.status, "statuses": update.statuses,
            "grew": [e.condition for e in record.expansions]})))

    def close(self) -> None:
        """Let the subscribers that have matched get what was published (up to
        CLOSE_WAIT seconds) before the robot's node goes.

        Discovery matches each topic on its own: a monitor that joined late may hear
        the statuses already and not yet be matched on the tree, which it gets, kept,
        only once it is. So the tree waits for as many subscribers as the statuses have
        (up to CLOSE_WAIT), then each waits for its acknowledgements (as long again)."""
        import time

        from rclpy.duration import Duration

        until = time.monotonic() + CLOSE_WAIT
        while (self.tree.get_subscription_count() < self.statuses.get_subscription_count()
               and time.monotonic() < until):
            time.sleep(0.01)
        for publisher in (self.tree, self.statuses):
            publisher.wait_for_all_acked(Duration(seconds=CLOSE_WAIT))
