"""The built-in nodes of BehaviorTree.CPP 4 and their ports, as the reader checks them.

Checked against the factory of BT.CPP 4.8 (the version the tests load) and of 4.10
(which adds TryCatch): every ID it registers by itself, the kind of each, how many
children it takes and the ports it declares, with their defaults. Custom nodes are
described by a TreeNodesModel instead (`btcpp_models`).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class PortSpec:
    """One port: direction (input/output/inout), BT.CPP type name, default if any."""

    name: str
    direction: str = "input"
    type: str = "std::string"
    default: str | None = None


@dataclass(frozen=True, slots=True)
class BuiltinSpec:
    """What the reader checks of one built-in node: its kind, the ports it declares and how
    many children it takes (`max_children` None: no upper bound, 0: a leaf)."""
    kind: str  # Control, Decorator, Action, Condition, SubTree
    ports: tuple[PortSpec, ...] = ()
    min_children: int = 0
    max_children: int | None = 0

    def port(self, name: str) -> PortSpec | None:
        """The declared port of that name, or None: an attribute that names no port is refused
        with the list of ports, which is how a typo in the XML shows."""
        for port in self.ports:
            if port.name == name:
                return port
        return None


def _control(*ports: PortSpec, least: int = 1, most: int | None = None) -> BuiltinSpec:
    return BuiltinSpec("Control", ports, least, most)


def _decorator(*ports: PortSpec) -> BuiltinSpec:
    return BuiltinSpec("Decorator", ports, 1, 1)


def _leaf(kind: str, *ports: PortSpec) -> BuiltinSpec:
    return BuiltinSpec(kind, ports)


_STATUS = "BT::NodeStatus"
_LOOP = {"Int": "int", "Double": "double", "String": "std::string", "Bool": "bool"}

BUILTINS: dict[str, BuiltinSpec] = {
    "Sequence": _control(),
    "ReactiveSequence": _control(),
    "SequenceWithMemory": _control(),
    "AsyncSequence": _control(),
    "Fallback": _control(),
    "ReactiveFallback": _control(),
    "AsyncFallback": _control(),
    "Parallel": _control(PortSpec("success_count", type="int", default="-1"),
                         PortSpec("failure_count", type="int", default="1")),
    "ParallelAll": _control(PortSpec("max_failures", type="int", default="1")),
    "IfThenElse": _control(least=2, most=3),
    "WhileDoElse": _control(least=2, most=3),
    "TryCatch": _control(PortSpec("catch_on_halt", type="bool", default="false"), least=2),
    **{f"Switch{n}": _control(PortSpec("variable"),
                              *(PortSpec(f"case_{i}") for i in range(1, n + 1)),
                              least=n + 1, most=n + 1)
       for n in range(2, 7)},
    "Inverter": _decorator(),
    "ForceSuccess": _decorator(),
    "ForceFailure": _decorator(),
    "KeepRunningUntilFailure": _decorator(),
    "RetryUntilSuccessful": _decorator(PortSpec("num_attempts", type="int")),
    "Repeat": _decorator(PortSpec("num_cycles", type="int")),
    "Timeout": _decorator(PortSpec("msec", type="unsigned int")),
    "Delay": _decorator(PortSpec("delay_msec", type="unsigned int")),
    "RunOnce": _decorator(PortSpec("then_skip", type="bool", default="true")),
    "Precondition": _decorator(PortSpec("if"), PortSpec("else", type=_STATUS, default="FAILURE")),
    **{f"Loop{item}": _decorator(
        PortSpec("queue", "inout", f"std::shared_ptr<std::deque<{cxx}>>"),
        PortSpec("if_empty", type=_STATUS, default="SUCCESS"),
        PortSpec("value", "output", cxx))
       for item, cxx in _LOOP.items()},
    "SkipUnlessUpdated": _decorator(PortSpec("entry")),
    "WaitValueUpdate": _decorator(PortSpec("entry")),
    "AlwaysSuccess": _leaf("Action"),
    "AlwaysFailure": _leaf("Action"),
    "Script": _leaf("Action", PortSpec("code")),
    "ScriptCondition": _leaf("Condition", PortSpec("code")),
    "SetBlackboard": _leaf("Action", PortSpec("value", type="AnyTypeAllowed"),
                           PortSpec("output_key", "inout", "AnyTypeAllowed")),
    "UnsetBlackboard": _leaf("Action", PortSpec("key")),
    "Sleep": _leaf("Action", PortSpec("msec", type="unsigned int")),
    "WasEntryUpdated": _leaf("Action", PortSpec("entry")),
    "SubTree": BuiltinSpec("SubTree", (PortSpec("_autoremap", type="bool", default="false"),)),
}
"""Every ID BehaviorTree.CPP 4.8's factory registers by itself, and TryCatch (4.10)."""

PRE_POST = ("_failureIf", "_successIf", "_skipIf", "_while",
            "_onSuccess", "_onFailure", "_post", "_onHalted")
"""The script attributes any node may carry (BT.CPP 4)."""

EXPLICIT_TAGS = ("Action", "Condition", "Control", "Decorator")
"""Tags of the explicit form `<Action ID="Pick" .../>`."""


__all__ = ["BUILTINS", "EXPLICIT_TAGS", "PRE_POST", "BuiltinSpec", "PortSpec"]
