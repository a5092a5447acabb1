"""BehaviorTree.CPP v4 XML: export for BT.CPP and Groot2, and import of the same subset.

Export writes every node in the compact form (`<Pick o="cube"/>`), since BT.CPP
rejects `<Action ID=...>` under a ReactiveSequence; reactive composites become
ReactiveSequence/ReactiveFallback and memory ones Sequence/Fallback. Leaves use one ID
per predicate or action template, grounded arguments go in ports named after the
parameters, and a TreeNodesModel declares every leaf ID with its ports, which Groot2
needs. Timeout counts ticks in btplan and milliseconds in BT.CPP: one tick is
TICK_MS milliseconds both ways.
"""

from __future__ import annotations

import math
import re
from xml.sax.saxutils import quoteattr

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import ForceFailure, ForceSuccess, Inverter, Retry, Timeout
from btplan.bt.formats.locate import line_at
from btplan.bt.formats.xmlparse import Element as _Element
from btplan.bt.formats.xmlparse import parse_xml
from btplan.bt.leaves import Action, Condition, Leaf, leaf_label
from btplan.bt.node import Node
from btplan.bt.parallel import Parallel
from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError, Span

TICK_MS = 100
"""Milliseconds per tick when a Timeout crosses to BT.CPP (btplan acts at 10 Hz)."""

_BAD_ID = re.compile(r"[\s<>&\"'/\\:*?|.]|[\x00-\x1f]")
_PORT = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_RESERVED_PORTS = {"name", "ID", "_autoremap"}
_RESERVED_IDS = {"Root", "root"}
_BUILTIN = {"ReactiveSequence", "ReactiveFallback", "Sequence", "Fallback", "Parallel",
            "Inverter", "ForceSuccess", "ForceFailure", "RetryUntilSuccessful", "Timeout"}


class ExportError(InputError):
    """The tree cannot be written as BT.CPP XML (an ID or port BT.CPP would reject)."""


# --- export -------------------------------------------------------------------------------


def _control(node: Node) -> tuple[str, list[tuple[str, str]]]:
    """Tag and parameter attributes of a non-leaf node."""
    if isinstance(node, Sequence):
        return ("Sequence" if node.memory else "ReactiveSequence"), []
    if isinstance(node, Fallback):
        return ("Fallback" if node.memory else "ReactiveFallback"), []
    if isinstance(node, Parallel):
        return "Parallel", [("success_count", str(node.success)),
                            ("failure_count", str(node.failure))]
    if isinstance(node, Retry):
        return "RetryUntilSuccessful", [("num_attempts", str(node.attempts))]
    if isinstance(node, Timeout):
        return "Timeout", [("msec", str(node.ticks * TICK_MS))]
    for kind in (Inverter, ForceSuccess, ForceFailure):
        if isinstance(node, kind):
            return kind.kind, []
    raise ExportError(f"no BehaviorTree.CPP node for {node.kind}")


def _check_leaf(leaf: Leaf, models: dict[str, tuple[str, tuple[str, ...]]]) -> None:
    if not leaf.ident or _BAD_ID.search(leaf.ident) or leaf.ident in _RESERVED_IDS | _BUILTIN:
        raise ExportError(f"{leaf.ident!r} cannot be a BehaviorTree.CPP node ID")
    for port in leaf.ports:
        if not _PORT.fullmatch(port) or port in _RESERVED_PORTS:
            raise ExportError(f"{port!r} (of {leaf.ident}) cannot be a BehaviorTree.CPP port")
    declared = models.setdefault(leaf.ident, (leaf.kind, leaf.ports))
    if declared != (leaf.kind, leaf.ports):
        raise ExportError(f"{leaf.ident} is used as {declared[0]}{list(declared[1])} and as "
                          f"{leaf.kind}{list(leaf.ports)}; one ID needs one kind and port list")


def _write(node: Node, depth: int, out: list[str],
           models: dict[str, tuple[str, tuple[str, ...]]]) -> None:
    pad = "  " * depth
    attrs: list[tuple[str, str]] = []
    if isinstance(node, Leaf):
        _check_leaf(node, models)
        tag = node.ident
        if node.name != leaf_label(node.ident, node.args):
            attrs.append(("name", node.name))
        attrs.extend(zip(node.ports, node.args, strict=True))
    else:
        tag, params = _control(node)
        if node.name:
            attrs.append(("name", node.name))
        attrs.extend(params)
    text = "".join(f" {k}={quoteattr(v)}" for k, v in attrs)
    if not node.children:
        out.append(f"{pad}<{tag}{text}/>")
        return
    out.append(f"{pad}<{tag}{text}>")
    for child in node.children:
        _write(child, depth + 1, out, models)
    out.append(f"{pad}</{tag}>")


def dump_xml(tree: BehaviorTree) -> str:
    """The tree as a BT.CPP v4 document with its TreeNodesModel."""
    if _BAD_ID.search(tree.name) or tree.name in _RESERVED_IDS or not tree.name:
        raise ExportError(f"{tree.name!r} cannot be a BehaviorTree.CPP tree ID")
    models: dict[str, tuple[str, tuple[str, ...]]] = {}
    body: list[str] = []
    _write(tree.root, 2, body, models)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<root BTCPP_format="4" main_tree_to_execute={quoteattr(tree.name)}>',
           f"  <BehaviorTree ID={quoteattr(tree.name)}>", *body, "  </BehaviorTree>",
           "  <TreeNodesModel>"]
    for ident in sorted(models):
        kind, ports = models[ident]
        if not ports:
            out.append(f"    <{kind} ID={quoteattr(ident)}/>")
            continue
        out.append(f"    <{kind} ID={quoteattr(ident)}>")
        out.extend(f'      <input_port name={quoteattr(p)} type="std::string"/>' for p in ports)
        out.append(f"    </{kind}>")
    out += ["  </TreeNodesModel>", "</root>"]
    return "\n".join(out) + "\n"


# --- import -------------------------------------------------------------------------------


class _Reader:
    """Turns parsed elements into nodes; every error names the element's place."""

    def __init__(self, text: str, path: str) -> None:
        self.text, self.path = text, path
        self.models: dict[str, tuple[str, tuple[str, ...]]] = {}

    def error(self, element: _Element, message: str, hint: str | None = None) -> InputError:
        return InputError(message, Span(self.path, element.line, element.column), hint,
                          line_at(self.text, element.line))

    def tree(self, root: _Element) -> BehaviorTree:
        if root.tag != "root":
            raise self.error(root, f"expected <root>, found <{root.tag}>")
        if root.attrs.get("BTCPP_format") != "4":
            raise self.error(root, "only BehaviorTree.CPP format 4 is read",
                             'write <root BTCPP_format="4" ...>')
        trees = {e.attrs.get("ID", ""): e for e in root.children if e.tag == "BehaviorTree"}
        for element in root.children:
            if element.tag == "TreeNodesModel":
                self.read_models(element)
            elif element.tag != "BehaviorTree":
                raise self.error(element, f"unexpected <{element.tag}> in <root>")
        main = root.attrs.get("main_tree_to_execute") or (next(iter(trees)) if len(trees) == 1
                                                           else "")
        if main not in trees:
            raise self.error(root, f"no <BehaviorTree ID=\"{main}\"> to execute",
                             "set main_tree_to_execute to one of: " + ", ".join(sorted(trees)))
        element = trees[main]
        if len(element.children) != 1:
            raise self.error(element, "a <BehaviorTree> has exactly one child")
        return BehaviorTree(self.node(element.children[0]), name=main)

    def read_models(self, models: _Element) -> None:
        for entry in models.children:
            ident = entry.attrs.get("ID", "")
            if entry.tag not in ("Action", "Condition") or not ident:
                continue  # SubTree, Control and Decorator entries describe nothing we build
            ports = tuple(p.attrs.get("name", "") for p in entry.children
                          if p.tag == "input_port")
            self.models[ident] = (entry.tag, ports)

    def node(self, element: _Element) -> Node:
        tag, attrs = element.tag, dict(element.attrs)
        if tag in ("Action", "Condition") and "ID" in attrs:
            tag = attrs.pop("ID")
        if tag in self.models:
            return self.leaf(element, tag, attrs)
        name = attrs.pop("name", "")
        children = [self.node(c) for c in element.children]
        node = self.control(element, tag, attrs, children, name)
        if attrs:
            raise self.error(element, f"<{tag}> has no attribute {min(attrs)!r}")
        return node

    def number(self, element: _Element, attrs: dict[str, str], key: str, default: str) -> int:
        value = attrs.pop(key, default)
        try:
            return int(value)
        except ValueError:
            raise self.error(element, f"{key}={value!r} is not a whole number") from None

    def control(self, element: _Element, tag: str, attrs: dict[str, str],
                children: list[Node], name: str) -> Node:
        composite = {"ReactiveSequence": (Sequence, False), "Sequence": (Sequence, True),
                     "ReactiveFallback": (Fallback, False), "Fallback": (Fallback, True)}
        if tag in composite:
            kind, memory = composite[tag]
            return kind(children, name=name, memory=memory)
        if tag == "Parallel":
            success = self.number(element, attrs, "success_count", "-1")
            failure = self.number(element, attrs, "failure_count", "1")
            return Parallel(children, success=success, failure=failure, name=name)
        decorators = ("Inverter", "ForceSuccess", "ForceFailure", "RetryUntilSuccessful",
                      "Timeout")
        if tag not in decorators:
            raise self.error(element, f"unknown node <{tag}>",
                             "leaf IDs must be declared in <TreeNodesModel>")
        if len(children) != 1:
            raise self.error(element, f"<{tag}> needs exactly one child, not {len(children)}")
        if tag == "RetryUntilSuccessful":
            attempts = self.number(element, attrs, "num_attempts", "1")
            if attempts < 1:
                raise self.error(element, f"num_attempts={attempts} is not supported",
                                 "btplan retries a fixed number of times, at least 1")
            return Retry(children[0], attempts=attempts, name=name)
        if tag == "Timeout":
            msec = self.number(element, attrs, "msec", str(TICK_MS))
            if msec < 1:
                raise self.error(element, f"msec={msec} leaves no time to run")
            return Timeout(children[0], ticks=math.ceil(msec / TICK_MS), name=name)
        plain = {"Inverter": Inverter, "ForceSuccess": ForceSuccess, "ForceFailure": ForceFailure}
        return plain[tag](children[0], name=name)

    def leaf(self, element: _Element, ident: str, attrs: dict[str, str]) -> Node:
        kind, ports = self.models[ident]
        if element.children:
            raise self.error(element, f"the {kind} {ident} cannot have children")
        name = attrs.pop("name", "")
        missing = [p for p in ports if p not in attrs]
        if missing:
            raise self.error(element, f"{ident} is missing port {missing[0]!r}",
                             f"{ident} declares ports: {', '.join(ports)}")
        args = tuple(attrs.pop(p) for p in ports)
        if attrs:
            raise self.error(element, f"{ident} has no port {min(attrs)!r}",
                             "declare it in <TreeNodesModel> or remove it")
        leaf_type = Action if kind == "Action" else Condition
        return leaf_type(ident, args, ports, name=name)


def load_xml(text: str, path: str = "<tree>") -> BehaviorTree:
    """Read a BT.CPP v4 document written by btplan or by hand in the same subset."""
    return _Reader(text, path).tree(parse_xml(text, path))


__all__ = ["TICK_MS", "ExportError", "dump_xml", "load_xml"]
