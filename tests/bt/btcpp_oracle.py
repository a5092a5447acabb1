"""Run an exported tree in the real BehaviorTree.CPP (behaviortreepy) beside btplan's engine.

behaviortreepy registers leaves without ports, so the copy given to BT.CPP has its
port attributes checked against the TreeNodesModel and then removed; each leaf gets a
unique instance name through which the callbacks find its grounded key.
"""

from __future__ import annotations

import contextlib
import os
import sys
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator

from btplan.bt import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.world import LeafKey, World

CONTROL = {"ReactiveSequence", "ReactiveFallback", "Sequence", "Fallback", "Parallel",
           "Inverter", "ForceSuccess", "ForceFailure", "RetryUntilSuccessful", "Timeout"}


def declared_models(xml: str) -> dict[str, tuple[str, list[str]]]:
    root = ET.fromstring(xml)
    models = root.find("TreeNodesModel")
    assert models is not None, "TreeNodesModel is missing"
    return {e.attrib["ID"]: (e.tag, [p.attrib["name"] for p in e.iter("input_port")])
            for e in models}


def port_free_copy(xml: str) -> tuple[str, dict[str, LeafKey]]:
    """Check leaf ports against the model, strip them, name each leaf uniquely."""
    models = declared_models(xml)
    root = ET.fromstring(xml)
    keys: dict[str, LeafKey] = {}
    body = root.find("BehaviorTree")
    assert body is not None
    for element in body.iter():
        if element.tag in CONTROL or element.tag == "BehaviorTree":
            continue
        assert element.tag in models, f"{element.tag} is not declared in TreeNodesModel"
        ports = models[element.tag][1]
        given = [k for k in element.attrib if k != "name"]
        assert given == ports, f"{element.tag}: ports {given} but declared {ports}"
        token = f"leaf{len(keys)}"
        keys[token] = (element.tag, tuple(element.attrib[p] for p in ports))
        element.attrib.clear()
        element.set("name", token)
    model = root.find("TreeNodesModel")
    assert model is not None
    root.remove(model)
    return ET.tostring(root, encoding="unicode"), keys


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Send BT.CPP's C-level prints on fd 1 to /dev/null while it loads and ticks."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as sink:
            os.dup2(sink.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


class BtcppRun:
    """The exported tree inside BT.CPP, its leaves answering from a ScriptWorld."""

    def __init__(self, xml: str, world: World) -> None:
        import behaviortreepy as bt

        self.bt, self.world = bt, world
        text, self.keys = port_free_copy(xml)
        factory = bt.BehaviorTreeFactory()
        for ident, (kind, _) in sorted(declared_models(xml).items()):
            if kind == "Condition":
                factory.register_simple_condition(ident, self._condition)
            else:
                factory.register_simple_stateful_action(
                    ident, self._call(world.start), self._call(world.step), self._halted)
        with quiet_stdout():
            self.tree = factory.create_tree_from_text(text)

    def _status(self, status: Status) -> object:
        names = {SUCCESS: "SUCCESS", FAILURE: "FAILURE", RUNNING: "RUNNING"}
        return getattr(self.bt.NodeStatus, names[status])

    def _condition(self, node: object) -> object:
        ok = self.world.check(self.keys[node.name()])  # type: ignore[attr-defined]
        return self._status(SUCCESS if ok else FAILURE)

    def _call(self, method: Callable[[LeafKey], Status]) -> Callable[[object], object]:
        return lambda node: self._status(method(self.keys[node.name()]))  # type: ignore[attr-defined]

    def _halted(self, node: object) -> None:
        self.world.halt(self.keys[node.name()])  # type: ignore[attr-defined]

    def tick(self) -> Status:
        with quiet_stdout():
            return Status(self.tree.tick_exactly_once().name)
