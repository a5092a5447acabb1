"""A fake robot on ROS 2 for the paper's Example 2: action servers and state topics.

    python examples/ros/fake_robot.py --sphere-rolls --take-cube
    btplan run domains/pick_place_obstacle.bt --ros examples/ros/example2.toml --hz 10

Action servers (test_msgs/action/NestedMessage; the goal's int fields carry the ids of
example2.toml's [tables.id]): /robot/move_to (place, trajectory), /robot/pick (object),
/robot/place (object, place), /robot/drop (object). Each takes its time, then changes
the world; a cancel stops it where it is. Topics (std_msgs/String, 20 times a second):
/robot/near (the robot's place and the objects there), /robot/holding, /world/on
(object:place pairs), /world/blocking (object:trajectory pairs). A service
(std_srvs/srv/Trigger), /robot/hand_empty, answers whether the hand is empty.

What others do, on request: `--sphere-rolls`, once the cube is picked, rolls the sphere
onto the path to the goal; `--take-cube`, the first time the robot sets off to the
goal with the cube, takes it out of the gripper and puts it back where it was.
For the tests: `--abort ACTION` aborts that action's first goal, `--never-finish
ACTION` accepts its goals and never ends them, `--silent TOPIC` never publishes TOPIC.
Every goal, result and cancel is printed, one line each, after its time.
"""

from __future__ import annotations

import argparse
import sys
import threading
import time
import tomllib
from pathlib import Path

import rclpy
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.executors import MultiThreadedExecutor
from std_msgs.msg import String
from std_srvs.srv import Trigger
from test_msgs.action import NestedMessage

SECONDS = {"move_to": 0.8, "pick": 0.5, "place": 0.5, "drop": 0.3}


def say(text: str) -> None:
    """One line of what happened, after the wall-clock time it happened at."""
    print(f"{time.time():.4f} {text}", flush=True)


class World:
    """The fake robot's world: where the robot, the objects and the hand are."""

    def __init__(self) -> None:
        self.lock = threading.Lock()
        self.robot_at = "start"
        self.holding = ""
        self.objects = {"cube": "cube", "sphere": "sphere"}  # object -> the place it lies at
        self.blocking: set[str] = set()
        self.on: set[str] = set()

    def topics(self) -> dict[str, str]:
        with self.lock:
            near = [self.robot_at, *(o for o, at in self.objects.items()
                                     if at == self.robot_at and o != self.holding)]
            return {"/robot/near": ",".join(p for p in near if p),
                    "/robot/holding": self.holding,
                    "/world/on": ",".join(sorted(self.on)),
                    "/world/blocking": ",".join(sorted(self.blocking))}


class FakeRobot:
    def __init__(self, args: argparse.Namespace) -> None:
        table = tomllib.loads(Path(args.bindings).read_text())["tables"]["id"]
        self.names = {number: name for name, number in table.items()}
        self.args, self.world = args, World()
        self.node = rclpy.create_node("fake_robot")
        self.first: dict[str, bool] = {}
        self.taken = False
        self.rolled = False
        self.asked = False
        self.publishers = {topic: self.node.create_publisher(String, topic, 10)
                           for topic in World().topics() if topic not in args.silent}
        self.node.create_timer(0.05, self.publish)
        self.node.create_service(Trigger, "/robot/hand_empty", self.hand_empty)
        for server in SECONDS:
            ActionServer(self.node, NestedMessage, f"/robot/{server}",
                         execute_callback=self.executor_for(server),
                         goal_callback=lambda goal: GoalResponse.ACCEPT,
                         cancel_callback=self.cancelled(server))

    def publish(self) -> None:
        for topic, text in self.world.topics().items():
            if topic in self.publishers:
                self.publishers[topic].publish(String(data=text))

    def hand_empty(self, request: Trigger.Request, response: Trigger.Response
                   ) -> Trigger.Response:
        if not self.asked:
            self.asked = True
            say("first call of /robot/hand_empty")
        with self.world.lock:
            response.success = self.world.holding == ""
            response.message = self.world.holding
        return response

    def cancelled(self, server: str):  # noqa: ANN201
        def accept(goal_handle: object) -> CancelResponse:
            say(f"cancel {server}")
            return CancelResponse.ACCEPT
        return accept

    def executor_for(self, server: str):  # noqa: ANN201
        def execute(goal_handle):  # noqa: ANN001, ANN202
            fields = goal_handle.request.nested_field
            first = self.names.get(fields.int32_value, "?")
            second = self.names.get(fields.int16_value, "")
            say(f"goal {server} {first} {second}".rstrip())
            once = not self.first.get(server)
            self.first[server] = True
            if server in self.args.abort and once:
                goal_handle.abort()
                say(f"aborted {server}")
                return NestedMessage.Result()
            if server == "move_to":
                self.setting_off(first)
            started = time.monotonic()
            while server in self.args.never_finish or \
                    time.monotonic() - started < SECONDS[server] / self.args.speed:
                if goal_handle.is_cancel_requested:
                    goal_handle.canceled()
                    say(f"cancelled {server}")
                    return NestedMessage.Result()
                time.sleep(0.01)
            ok = self.finish(server, first, second)
            if ok:
                goal_handle.succeed()
            else:
                goal_handle.abort()
            say(f"{'succeeded' if ok else 'aborted'} {server} {first}")
            return NestedMessage.Result()
        return execute

    def setting_off(self, place: str) -> None:
        world = self.world
        with world.lock:
            carrying = world.holding == "cube"
            world.robot_at = ""  # on the way
        if self.args.take_cube and place == "goal" and carrying and not self.taken \
                and not world.blocking:
            self.taken = True
            time.sleep(0.2 / self.args.speed)
            with world.lock:
                world.holding = ""
                world.objects["cube"] = "cube"
            say("someone took the cube out of the gripper")

    def finish(self, server: str, first: str, second: str) -> bool:
        world = self.world
        with world.lock:
            if server == "move_to":
                if any(pair.endswith(":" + second) for pair in world.blocking):
                    return False  # the path is blocked: stuck before the obstacle
                world.robot_at = world.objects.get(first, first)  # to an object: where it lies
                return True
            if server == "pick":
                if world.holding or world.objects.get(first) != world.robot_at:
                    return False
                world.holding = first
                world.on = {pair for pair in world.on if not pair.startswith(first + ":")}
                rolls = self.args.sphere_rolls and first == "cube" and not self.rolled
                self.rolled = self.rolled or rolls
            elif server == "place":
                if world.holding != first or world.robot_at != second:
                    return False
                world.holding = ""
                world.objects[first] = second
                world.on.add(f"{first}:{second}")
                world.blocking = {p for p in world.blocking if not p.startswith(first + ":")}
                return True
            else:  # drop
                if world.holding != first:
                    return False
                world.holding = ""
                world.objects[first] = world.robot_at
                return True
        if rolls:
            with world.lock:
                world.blocking.add("sphere:tau_goal")
            say("the sphere rolled onto the path to the goal")
        return True


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bindings", default=str(Path(__file__).with_name("example2.toml")))
    parser.add_argument("--sphere-rolls", action="store_true")
    parser.add_argument("--take-cube", action="store_true")
    parser.add_argument("--abort", action="append", default=[], metavar="ACTION")
    parser.add_argument("--never-finish", action="append", default=[], metavar="ACTION")
    parser.add_argument("--silent", action="append", default=[], metavar="TOPIC")
    parser.add_argument("--speed", type=float, default=1.0, help="time runs this much faster")
    args = parser.parse_args()
    rclpy.init()
    robot = FakeRobot(args)
    executor = MultiThreadedExecutor(num_threads=8)
    executor.add_node(robot.node)
    say("fake robot ready")
    try:
        executor.spin()
    except KeyboardInterrupt:
        pass
    finally:
        executor.shutdown()
        rclpy.try_shutdown()
    sys.exit(0)


if __name__ == "__main__":
    main()
