"""`RosRobot`: the domain's actions as ROS 2 action goals, its conditions as topics and
services, behind the robot contract (btplan.robot.Robot).

An action leaf's start sends a goal to its action server; the loop polls it each tick:
RUNNING until the result, SUCCESS when the goal succeeded (once every state topic has
said something since, so that the loop reads the action's effects, not the state before
it: SETTLE), FAILURE when it was rejected,
aborted or cancelled, or no answer came within the binding's timeouts (the reason is
the failure's message in the trace). Halting an action cancels its goal; `stopped`
answers once the server has answered the cancel (or `cancel_wait` has passed), which
the loop waits for on every way out of a run. A condition reads the latest message of
its topic (false when none came within `stale_after`, and `dead_ends` says so), or
calls its service.

The node is spun by an executor in a thread of its own: the loop's calls never wait
for the middleware, except a service condition, for at most its `timeout`.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.errors import WorldError
from btplan.model import Task
from btplan.records import replace
from btplan.robot.api import Robot
from btplan.ros.bindings import ActionBinding, Bindings, ConditionBinding, field_paths, message_type

__all__ = ["SETTLE", "GoalSkill", "RosRobot", "rclpy_origin"]

SETTLE = 0.5
"""Seconds a succeeded goal waits, at most, for the state topics to show its effects."""


def rclpy_origin() -> str:
    """Which rclpy runs: its version and where it comes from (a sourced ROS 2, or the
    PyPI wheels)."""
    import rclpy

    where = rclpy.__file__ or "?"
    source = "the PyPI wheels" if "site-packages" in where and "/opt/ros/" not in where \
        else "a sourced ROS 2 install"
    try:
        from importlib.metadata import version

        number = version("ros-kilted-rclpy")
    except Exception:  # noqa: BLE001 (a sourced install has no such distribution)
        number = "?"
    return f"rclpy {number} from {source} ({where})"


class RosRobot(Robot):
    """A robot on ROS 2, made from a binding file (module docstring)."""

    def __init__(self, bindings: Bindings, task: Task) -> None:
        super().__init__()
        import rclpy
        from rclpy.executors import SingleThreadedExecutor

        self.bindings, self.task = bindings, task
        self.settings = bindings.ros
        self.capabilities = replace(self.capabilities, dead_ends=True)
        self.context = rclpy.Context()
        rclpy.init(context=self.context)
        self.node = rclpy.create_node(self.settings.node, context=self.context)
        self._executor = SingleThreadedExecutor(context=self.context)
        self._executor.add_node(self.node)
        self._spinning = threading.Thread(target=self._spin, name="ros-executor", daemon=True)
        self._spinning.start()
        self._latest: dict[str, tuple[Any, float]] = {}
        self._subscribed: set[str] = set()
        self._why: dict[str, str] = {}
        self._clients: dict[str, Any] = {}
        for name, action in sorted(bindings.actions.items()):
            self._bind_action(name, action)
        for name, condition in sorted(bindings.conditions.items()):
            self._bind_condition(name, condition)
        self.active: set[GoalSkill] = set()
        self.goals_sent = 0

    def _spin(self) -> None:
        from rclpy.executors import ExternalShutdownException

        try:
            self._executor.spin()
        except (ExternalShutdownException, Exception):  # noqa: BLE001 (shut down)
            pass

    # --- actions ------------------------------------------------------------------------

    def _bind_action(self, name: str, action: ActionBinding) -> None:
        from rclpy.action.client import ActionClient

        kind = message_type(action.type)
        client: Any = ActionClient(self.node, kind, action.server)
        self._clients[name] = client
        fields = field_paths(kind.Goal)
        expressions = self.bindings.goals[name]
        params = [p.name for p in self.task.domain.action_map[name].parameters]

        def start(*args: str) -> GoalSkill:
            goal = kind.Goal()
            names = {**self.bindings.tables, **dict(zip(params, args, strict=True))}
            for field, expression in expressions.items():
                _set(goal, field, _as_field(expression(names), fields[field]))
            skill = GoalSkill(self, f"{name}({', '.join(args)})", action.server, client, goal)
            self.active.add(skill)
            self.goals_sent += 1
            return skill

        start.__signature__ = _signature(params)  # type: ignore[attr-defined]
        self.action(name)(start)

    def wait_for_servers(self) -> None:
        """Wait for every action server, then for the first message of every state topic
        (`server_wait` for each); a WorldError names the servers that did not come."""
        deadline = time.monotonic() + self.settings.server_wait
        missing = []
        for name, client in sorted(self._clients.items()):
            left = max(0.0, deadline - time.monotonic())
            if not client.wait_for_server(timeout_sec=left):
                missing.append(f"{self.bindings.actions[name].server} (for {name})")
        if missing:
            raise WorldError(f"no action server {', '.join(missing)} within "
                             f"{self.settings.server_wait:g} s")
        # The first tick reads every condition: let the state topics' first messages come,
        # within a wait of their own (a topic still silent then reads false, and dead_ends
        # says so).
        deadline = time.monotonic() + self.settings.server_wait
        while not self._subscribed <= set(self._latest) and time.monotonic() < deadline:
            time.sleep(0.01)

    # --- conditions ---------------------------------------------------------------------

    def _bind_condition(self, name: str, condition: ConditionBinding) -> None:
        predicate = next(p for p in self.task.domain.predicates if p.name == name)
        params = [p.name for p in predicate.parameters]
        test = self.bindings.tests[name]
        kind = message_type(condition.type)
        if condition.topic is not None:
            if condition.topic not in self._subscribed:  # conditions may share a topic
                self._subscribed.add(condition.topic)
                self._subscribe(condition.topic, kind)

            def read(*args: str) -> bool:
                return self._read_topic(name, condition, test, params, args)
        else:
            service: Any = self.node.create_client(kind, condition.service or "")
            fields = field_paths(kind.Request)

            def read(*args: str) -> bool:
                return self._call_service(name, condition, service, kind.Request, fields,
                                          params, args)

        read.__signature__ = _signature(params)  # type: ignore[attr-defined]
        self.condition(name)(read)

    def _subscribe(self, topic: str, kind: Any) -> None:
        def keep(message: Any) -> None:
            self._latest[topic] = (message, time.monotonic())

        self.node.create_subscription(kind, topic, keep, 10)

    def _read_topic(self, name: str, condition: ConditionBinding, test: Any,
                    params: list[str], args: tuple[str, ...]) -> bool:
        topic = condition.topic or ""
        latest = self._latest.get(topic)
        if latest is None:
            self._why[name] = f"{name}: no message on {topic} yet"
            return False
        message, at = latest
        age = time.monotonic() - at
        if condition.stale_after is not None and age > condition.stale_after:
            self._why[name] = (f"{name}: the last message on {topic} is {age:.1f} s old "
                               f"(stale after {condition.stale_after:g} s), so it reads false")
            return False
        self._why.pop(name, None)
        names = {**self.bindings.tables, **dict(zip(params, args, strict=True)), "msg": message}
        return bool(test(names))

    def _call_service(self, name: str, condition: ConditionBinding, client: Any,
                      make_request: Any, fields: dict[str, str], params: list[str],
                      args: tuple[str, ...]) -> bool:
        names = {**self.bindings.tables, **dict(zip(params, args, strict=True))}
        request = make_request()
        for field, expression in self.bindings.requests.get(name, {}).items():
            _set(request, field, _as_field(expression(names), fields[field]))
        future = client.call_async(request)
        deadline = time.monotonic() + condition.timeout
        while not future.done() and time.monotonic() < deadline:
            time.sleep(0.001)
        if not future.done():
            future.cancel()
            self._why[name] = (f"{name}: {condition.service} did not answer within "
                               f"{condition.timeout:g} s, so it reads false")
            return False
        self._why.pop(name, None)
        return bool(self.bindings.tests[name]({**names, "msg": future.result()}))

    def tree_topics(self) -> Any:
        """The run's monitor that publishes the tree on this node (`tree_topics`), or
        None when the binding file turns them off."""
        from btplan.ros.tree_topics import TreeTopics

        return TreeTopics(self.node, self.settings.tree_topics) if self.settings.tree_topics \
            else None

    def finished(self, skill: GoalSkill) -> None:
        """A goal ended (or was cancelled): it is no longer cancelled when the robot closes."""
        self.active.discard(skill)

    def caught_up(self, since: float) -> bool:
        """Whether every state topic has had a message since `since` (or SETTLE seconds
        have passed): a result can come before the topics that show its effects, and a
        loop that read them first would take the action for undone and start it again."""
        if time.monotonic() - since > SETTLE:
            return True
        return all(at > since for topic, (_, at) in self._latest.items())

    def dead_ends(self) -> list[str]:
        """Conditions that read false for want of news (stale topics, silent services)."""
        return sorted(self._why.values())

    # --- lifecycle ----------------------------------------------------------------------

    def close(self) -> None:
        """Cancel what still runs, then leave ROS: the node, the executor, the context."""
        for skill in list(self.active):
            skill.cancel()
        super().close()
        try:
            self._executor.shutdown(timeout_sec=1.0)
            self.node.destroy_node()
        finally:
            if self.context.ok():
                self.context.shutdown()
            self._spinning.join(timeout=2.0)


class GoalSkill:
    """One goal sent to an action server, polled by the loop (module docstring)."""

    def __init__(self, robot: RosRobot, what: str, server: str, client: Any, goal: Any) -> None:
        self.robot, self.what, self.server = robot, what, server
        self.settings = robot.settings
        self.sent = time.monotonic()
        self.accepted_at: float | None = None
        self.result_at: float | None = None
        """When the result came: SUCCESS waits for the state topics to catch up."""
        self._goal = client.send_goal_async(goal)
        self._handle: Any = None
        self._result: Any = None
        self._cancel: Any = None
        self._cancelled_at: float | None = None
        self.ended = False

    def poll(self) -> Status:
        """The goal's status now (see the module docstring); a failure raises WorldError
        with its reason, which the loop records as that action's FAILURE."""
        now = time.monotonic()
        if self._handle is None:
            if not self._goal.done():
                if now - self.sent > self.settings.accept_timeout:
                    self._end()
                    raise WorldError(f"{self.server} did not accept the goal "
                                     f"within {self.settings.accept_timeout:g} s")
                return RUNNING
            self._handle = self._goal.result()
            if not self._handle.accepted:
                self._end()
                raise WorldError(f"{self.server} rejected the goal")
            self.accepted_at = now
            self._result = self._handle.get_result_async()
        if not self._result.done():
            if self.accepted_at is not None and now - self.accepted_at > \
                    self.settings.result_timeout:
                self.cancel()
                raise WorldError(f"no result from {self.server} within "
                                 f"{self.settings.result_timeout:g} s; the goal was cancelled")
            return RUNNING
        from action_msgs.msg import GoalStatus

        status = self._result.result().status
        if status == GoalStatus.STATUS_SUCCEEDED:
            if self.result_at is None:
                self.result_at = now
            if not self.robot.caught_up(self.result_at):
                return RUNNING  # the state topics have not said what the action did yet
            self._end()
            return SUCCESS
        self._end()
        names = {GoalStatus.STATUS_ABORTED: "aborted", GoalStatus.STATUS_CANCELED: "cancelled"}
        raise WorldError(f"{self.server} {names.get(status, 'ended')} the goal")

    def cancel(self) -> None:
        """Ask the server to cancel the goal (once it is accepted; a goal not yet accepted
        is cancelled as soon as it is)."""
        if self.ended or self._cancel is not None:
            return
        self._cancelled_at = time.monotonic()
        if self._handle is None and self._goal.done():
            self._handle = self._goal.result()
        if self._handle is not None and self._handle.accepted:
            self._cancel = self._handle.cancel_goal_async()
        elif not self._goal.done():
            self._goal.add_done_callback(lambda f: self._late_cancel(f))
        self._end()

    def _late_cancel(self, future: Any) -> None:
        handle = future.result()
        if handle is not None and handle.accepted:
            self._cancel = handle.cancel_goal_async()

    def stopped(self) -> bool:
        """Whether the server answered the cancel (or `cancel_wait` passed)."""
        if self._cancelled_at is None:
            return True
        if self._cancel is not None and self._cancel.done():
            return True
        return time.monotonic() - self._cancelled_at > self.settings.cancel_wait

    def _end(self) -> None:
        self.ended = True
        self.robot.finished(self)


def _signature(params: list[str]) -> Any:
    """A signature of the parameters' names, for a function that takes them as *args
    (Robot checks a binding's arity against the domain)."""
    import inspect

    return inspect.Signature(
        [inspect.Parameter(p, inspect.Parameter.POSITIONAL_OR_KEYWORD) for p in params])


def _set(message: Any, path: str, value: Any) -> None:
    *parents, last = path.split(".")
    for part in parents:
        message = getattr(message, part)
    setattr(message, last, value)


def _as_field(value: Any, typename: str) -> Any:
    """A value as the field's type wants it (ints for int fields, ...)."""
    if typename.startswith(("int", "uint", "octet", "char")):
        return int(value)
    if typename in ("float", "double"):
        return float(value)
    if typename == "boolean":
        return bool(value)
    if typename.startswith("string"):
        return str(value)
    return value
