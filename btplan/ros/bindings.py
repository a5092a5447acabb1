"""The binding file of `btplan run DOMAIN --ros FILE.toml`: how the domain meets a robot.

    [ros]                                   # all optional
    node = "btplan"                         # the node's name
    server_wait = 5.0                       # s for every action server at start
    accept_timeout = 2.0                    # s for a goal to be accepted
    result_timeout = 60.0                   # s for its result
    cancel_wait = 2.0                       # s for a halted goal's cancel to be answered
    tree_topics = "/btplan"                 # the tree and statuses there ("" for none)

    [tables.id]                             # per-object lookup tables: id[o]
    cube = 1
    goal = 3

    [actions.Pick]                          # every action template of the domain
    type = "test_msgs/action/NestedMessage"
    server = "/robot/pick"
    goal = { "nested_field.int32_value" = "id[o]" }

    [conditions.holding]                    # every predicate the actions change
    topic = "/robot/holding"
    type = "std_msgs/msg/String"
    when = "msg.data == o"
    stale_after = 2.0                       # s; an older message reads false

    [conditions.ready]                      # or a service, asked at every check
    service = "/robot/ready"
    type = "std_srvs/srv/Trigger"
    when = "msg.success"                    # msg is the response

Every name is checked when the file is read: templates, predicates, parameters, message
types, fields and expressions; each error names the file and the line of its table.
"""

from __future__ import annotations

import importlib
import tomllib
from difflib import get_close_matches
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from btplan.errors import InputError, Span
from btplan.model import Domain
from btplan.ros.expressions import Expression, ExpressionError

__all__ = ["ActionBinding", "Bindings", "ConditionBinding", "RosSettings", "load_bindings",
           "message_type"]

ROS_HINT = "install ROS 2 for Python with: pip install 'btplan[ros]' (or source a ROS 2 install)"


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")


class RosSettings(_Strict):
    """The file's [ros] table: the node's name, the waits and timeouts, the tree topics."""

    node: str = "btplan"
    server_wait: float = Field(default=5.0, gt=0)
    accept_timeout: float = Field(default=2.0, gt=0)
    result_timeout: float = Field(default=60.0, gt=0)
    cancel_wait: float = Field(default=2.0, gt=0)
    tree_topics: str = "/btplan"


class ActionBinding(_Strict):
    """One [actions.NAME] table: the action type, its server, and each goal field's
    expression."""

    type: str
    server: str
    goal: dict[str, str] = {}


class ConditionBinding(_Strict):
    """One [conditions.NAME] table: a topic (or a service), its type, the test `when`,
    and how old a message may be."""

    topic: str | None = None
    service: str | None = None
    type: str
    when: str
    stale_after: float | None = Field(default=None, gt=0)
    request: dict[str, str] = {}
    timeout: float = Field(default=1.0, gt=0)
    """Seconds a service call may take (a service condition)."""


class Bindings(_Strict):
    """A whole binding file, checked, with each expression compiled (`load_bindings`)."""

    ros: RosSettings = Field(default_factory=RosSettings)
    tables: dict[str, dict[str, str | int | float | bool]] = {}
    actions: dict[str, ActionBinding] = {}
    conditions: dict[str, ConditionBinding] = {}
    path: str = ""
    goals: dict[str, dict[str, Expression]] = {}
    """Per action, each goal field's checked expression."""
    tests: dict[str, Expression] = {}
    """Per condition, its checked `when`."""
    requests: dict[str, dict[str, Expression]] = {}

    model_config = ConfigDict(extra="forbid", arbitrary_types_allowed=True)


def message_type(name: str) -> Any:
    """The class of `pkg/msg/Name`, `pkg/srv/Name` or `pkg/action/Name`."""
    parts = name.split("/")
    if len(parts) != 3 or parts[1] not in ("msg", "srv", "action") or not all(parts):
        raise ValueError(f"{name!r} is not a ROS 2 type name (pkg/msg/Name, pkg/srv/Name "
                         "or pkg/action/Name)")
    try:
        module = importlib.import_module(f"{parts[0]}.{parts[1]}")
    except ImportError:
        raise ValueError(f"no ROS 2 package {parts[0]!r} with {parts[1]} types is installed "
                         f"for {name!r}") from None
    found = getattr(module, parts[2], None)
    if found is None:
        raise ValueError(f"{parts[0]}/{parts[1]} has no type {parts[2]!r}")
    return found


def field_paths(kind: Any, prefix: str = "") -> dict[str, str]:
    """Every dotted field path of a message class (nested messages opened), and its type."""
    out: dict[str, str] = {}
    for name, typename in kind.get_fields_and_field_types().items():
        path = f"{prefix}{name}"
        out[path] = typename
        if "/" in typename and not typename.startswith(("sequence", "string")):
            package, _, inner = typename.partition("/")
            try:
                nested = getattr(importlib.import_module(f"{package}.msg"), inner)
            except (ImportError, AttributeError):
                continue
            out.update(field_paths(nested, path + "."))
    return out


def load_bindings(path: str, text: str, domain: Domain) -> Bindings:
    """Read and check a binding file against `domain` and the installed ROS 2 types."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        line = getattr(error, "lineno", 1) or 1
        raise InputError(f"not TOML: {error}", Span(path, line, 1)) from None
    try:
        bindings = Bindings.model_validate({**raw, "path": path})
    except ValidationError as error:
        first = error.errors()[0]
        where = ".".join(str(p) for p in first["loc"])
        raise InputError(f"{where}: {first['msg']}", Span(path, _line(text, where), 1)) from None
    _Checker(bindings, text, domain).check()
    return bindings


class _Checker:
    def __init__(self, bindings: Bindings, text: str, domain: Domain) -> None:
        self.b, self.text, self.domain = bindings, text, domain

    def error(self, where: str, message: str, hint: str | None = None) -> InputError:
        return InputError(f"{where}: {message}", Span(self.b.path, _line(self.text, where), 1),
                          hint)

    def check(self) -> None:
        templates = {a.name: a for a in self.domain.actions}
        predicates = {p.name: p for p in self.domain.predicates}
        for name in self.b.actions:
            if name not in templates:
                raise self.error(f"actions.{name}", f"the domain has no action {name!r}",
                                 _close(name, templates))
        for name in self.b.conditions:
            if name not in predicates:
                raise self.error(f"conditions.{name}", f"the domain has no predicate {name!r}",
                                 _close(name, predicates))
        for name in sorted(templates):
            if name not in self.b.actions:
                raise self.error("actions", f"no binding for the action {name!r}",
                                 f"add [actions.{name}] with its type, server and goal")
        for name in sorted(self.domain.changed_predicates):
            if name not in self.b.conditions:
                raise self.error("conditions", f"no binding for the condition {name!r} (an "
                                 "action changes it, so the robot must say whether it holds)",
                                 f"add [conditions.{name}] with a topic or a service")
        tables = set(self.b.tables)
        for name, action in self.b.actions.items():
            self._action(name, action, [p.name for p in templates[name].parameters], tables)
        for name, condition in self.b.conditions.items():
            self._condition(name, condition, [p.name for p in predicates[name].parameters],
                            tables)

    def _type(self, where: str, name: str) -> Any:
        try:
            import rclpy  # noqa: F401  (the types need the ROS 2 Python runtime)
        except ImportError:
            raise self.error(where, "ROS 2 is not installed for this Python", ROS_HINT) from None
        try:
            return message_type(name)
        except ValueError as error:
            raise self.error(where, str(error)) from None

    def _expression(self, where: str, text: str, names: set[str],
                    fields: set[str] | None = None) -> Expression:
        try:
            return Expression(text, names, fields)
        except ExpressionError as error:
            raise self.error(where, str(error)) from None

    def _action(self, name: str, action: ActionBinding, params: list[str],
                tables: set[str]) -> None:
        where = f"actions.{name}"
        kind = self._type(where, action.type)
        if "/action/" not in action.type:
            raise self.error(where, f"{action.type!r} is not an action type (pkg/action/Name)")
        fields = field_paths(kind.Goal)
        goal: dict[str, Expression] = {}
        for field, text in action.goal.items():
            if field not in fields:
                raise self.error(f"{where}.goal", f"the goal of {action.type} has no field "
                                 f"{field!r}", "fields: " + ", ".join(sorted(fields)))
            goal[field] = self._expression(f"{where}.goal", text, set(params) | tables)
        self.b.goals[name] = goal

    def _condition(self, name: str, condition: ConditionBinding, params: list[str],
                   tables: set[str]) -> None:
        where = f"conditions.{name}"
        if (condition.topic is None) == (condition.service is None):
            raise self.error(where, "give either a topic or a service")
        kind = self._type(where, condition.type)
        names = set(params) | tables
        if condition.topic is not None:
            if "/msg/" not in condition.type:
                raise self.error(where, f"{condition.type!r} is not a message type")
            read = set(field_paths(kind))
        else:
            if "/srv/" not in condition.type:
                raise self.error(where, f"{condition.type!r} is not a service type")
            read = set(field_paths(kind.Response))
            request = set(field_paths(kind.Request))
            self.b.requests[name] = {}
            for field, text in condition.request.items():
                if field not in request:
                    raise self.error(f"{where}.request", f"the request of {condition.type} "
                                     f"has no field {field!r}")
                self.b.requests[name][field] = self._expression(f"{where}.request", text, names)
        self.b.tests[name] = self._expression(f"{where}.when", condition.when, names | {"msg"},
                                              read)


def _close(name: str, known: dict[str, Any]) -> str | None:
    near = get_close_matches(name, list(known), n=1)
    return f"did you mean {near[0]!r}?" if near else None


def _line(text: str, where: str) -> int:
    """The line of the table `where` names ([actions.Pick] for actions.Pick.goal), or 1."""
    parts = where.split(".")
    for count in range(min(len(parts), 2), 0, -1):
        header = "[" + ".".join(parts[:count]) + "]"
        for number, line in enumerate(text.splitlines(), 1):
            if line.strip().startswith(header):
                return number
    return 1
