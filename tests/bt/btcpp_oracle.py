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


UNREADABLE = "<not readable as text>"


def _leaf_ids(root: ET.Element) -> dict[str, str]:
    """Custom leaf IDs and their kind, from the TreeNodesModel."""
    models = root.find("TreeNodesModel")
    return {e.attrib["ID"]: e.tag for e in (models if models is not None else [])
            if e.tag in ("Action", "Condition")}


def document_copy(xml: str) -> tuple[str, dict[str, tuple[str, list[tuple[str, str]]]]]:
    """The exported document as BT.CPP can load it with port-less Python leaves.

    Custom leaves lose their port attributes (kept aside, to build the key the world
    sees) and get a unique name; their `_` condition attributes, every built-in node and
    every SubTree stay as written.
    """
    root = ET.fromstring(xml)
    leaves = _leaf_ids(root)
    ports: dict[str, tuple[str, list[tuple[str, str]]]] = {}
    for tree in root.findall("BehaviorTree"):
        for element in tree.iter():
            if element.tag not in leaves:
                continue
            token = f"leaf{len(ports)}"
            given = [(k, v) for k, v in element.attrib.items()
                     if k != "name" and not k.startswith("_")]
            ports[token] = (element.tag, given)
            for key, _ in given:
                del element.attrib[key]
            element.set("name", token)
    model = root.find("TreeNodesModel")
    if model is not None:
        root.remove(model)
    return ET.tostring(root, encoding="unicode"), ports


class BtcppDocRun:
    """An imported-and-exported document inside BT.CPP, leaves answering from a world.

    A leaf's `{key}` port is read from the leaf's own blackboard in BT.CPP (SubTree
    remapping included), as btplan's engine reads it from its own.
    """

    def __init__(self, xml: str, world: World) -> None:
        import behaviortreepy as bt

        self.bt, self.world = bt, world
        text, self.ports = document_copy(xml)
        factory = bt.BehaviorTreeFactory()
        running: dict[str, LeafKey] = {}

        def key(node: object) -> LeafKey:
            ident, given = self.ports[node.name()]  # type: ignore[attr-defined]
            board = node.config().blackboard  # type: ignore[attr-defined]
            values = []
            for port, raw in given:
                inner = raw[1:-1] if raw.startswith("{") and raw.endswith("}") else None
                name = port if inner == "=" else inner
                try:
                    values.append(board.get_string(name) if name else raw)
                except Exception:  # noqa: BLE001 -- unset entry: the literal text, as btplan
                    values.append(raw)
            return ident, tuple(values)

        def start(node: object) -> object:
            running[node.name()] = key(node)  # type: ignore[attr-defined]
            return self._status(world.start(running[node.name()]))  # type: ignore[attr-defined]

        def step(node: object) -> object:
            return self._status(world.step(running[node.name()]))  # type: ignore[attr-defined]

        def halted(node: object) -> None:
            world.halt(running[node.name()])  # type: ignore[attr-defined]

        def check(node: object) -> object:
            return self._status(SUCCESS if world.check(key(node)) else FAILURE)

        for ident, kind in sorted(_leaf_ids(ET.fromstring(xml)).items()):
            if kind == "Condition":
                factory.register_simple_condition(ident, check)
            else:
                factory.register_simple_stateful_action(ident, start, step, halted)
        with quiet_stdout():
            self.tree = factory.create_tree_from_text(text)

    def _status(self, status: Status) -> object:
        return getattr(self.bt.NodeStatus, status.value)

    def tick(self) -> Status:
        with quiet_stdout():
            return Status(self.tree.tick_exactly_once().name)

    def board(self) -> dict[str, str]:
        board = self.tree.root_blackboard()
        out: dict[str, str] = {}
        for key in sorted(board.get_keys()):
            try:
                out[key] = board.get_string(key)
            except RuntimeError:
                out[key] = UNREADABLE  # never written, or not a text (a queue)
        return out
