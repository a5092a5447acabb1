"""A second fake robot for the ROS tests: domains/run_alternatives.bt's parcel, its van
and its drone. The road is closed: every Drive goal is aborted after a while; Load and
Fly succeed. State on /parcel/state (std_msgs/String): the facts that hold, comma
separated (`loaded:box`, `delivered:box`, `van_ready`, `drone_ready`)."""

from __future__ import annotations

import threading
import time

import rclpy
from rclpy.action import ActionServer, CancelResponse
from rclpy.executors import MultiThreadedExecutor
from std_msgs.msg import String
from test_msgs.action import NestedMessage

facts = {"van_ready", "drone_ready"}
lock = threading.Lock()


def say(text: str) -> None:
    print(f"{time.time():.4f} {text}", flush=True)


def server(name: str, seconds: float, effect: str | None, removes: str | None):  # noqa: ANN201
    def execute(goal_handle):  # noqa: ANN001, ANN202
        say(f"goal {name}")
        started = time.monotonic()
        while time.monotonic() - started < seconds:
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                say(f"cancelled {name}")
                return NestedMessage.Result()
            time.sleep(0.01)
        if effect is None:
            goal_handle.abort()
            say(f"aborted {name}")
            return NestedMessage.Result()
        with lock:
            facts.add(effect)
            facts.discard(removes)
        goal_handle.succeed()
        say(f"succeeded {name}")
        return NestedMessage.Result()
    return execute


def main() -> None:
    rclpy.init()
    node = rclpy.create_node("parcel_robot")
    out = node.create_publisher(String, "/parcel/state", 10)

    def publish() -> None:
        with lock:
            out.publish(String(data=",".join(sorted(facts))))

    node.create_timer(0.05, publish)
    for name, seconds, effect, removes in (("load", 0.2, "loaded:box", None),
                                           ("drive", 0.3, None, None),
                                           ("fly", 0.3, "delivered:box", "loaded:box")):
        ActionServer(node, NestedMessage, f"/parcel/{name}",
                     execute_callback=server(name, seconds, effect, removes),
                     cancel_callback=lambda handle: CancelResponse.ACCEPT)
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(node)
    say("fake robot ready")
    try:
        executor.spin()
    except KeyboardInterrupt:
        pass
    finally:
        executor.shutdown()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
