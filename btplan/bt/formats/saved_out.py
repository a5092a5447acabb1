"""Writing btplan's JSON tree format without its pydantic models.

`btplan plan` prints every tree it builds in this format, and importing pydantic and
validating a model per node cost more than planning a small problem. This writer
builds the same dictionaries that `SavedTree.model_dump(mode="json",
exclude_defaults=True)` gives (saved.py holds the models, the schema and the reader;
tests/bt/test_saved_json.py checks that the two agree), in the models' field order.

The text is written piece by piece, not by a `json.dumps` per key and value: a planned
tree of 1,500 nodes took 50 ms that way, longer than planning it. Strings that JSON
writes unchanged between quotes (printable, no quote or backslash) are quoted here, and
anything else is left to `json`, which is imported only then.
"""

from __future__ import annotations

import sys

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import Retry, Timeout
from btplan.bt.leaves import Leaf, leaf_label
from btplan.bt.node import Node
from btplan.bt.status import IDLE
from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError

TYPE_CHECKING = False
if TYPE_CHECKING:
    from collections.abc import Iterator
    from typing import Any

    from btplan.bt.parallel import Parallel

FORMAT = "btplan-tree"
VERSION = 1
DEFAULT_NAME = "Main"
NODE_TYPES = ("Sequence", "Fallback", "Parallel", "Inverter", "ForceSuccess", "ForceFailure",
              "Retry", "Timeout", "Condition", "Action")


def representable(node: Node) -> None:
    """Refuse, with a clear error, what only BT.CPP XML can hold (its other built-ins,
    custom controls, condition scripts, retrying for ever)."""
    kind = node.kind
    if kind not in NODE_TYPES or (node.origin is not None and node.origin.guard is not None):
        what = node.origin.tag if node.origin is not None else kind
        raise InputError(f"{what} cannot be saved in btplan's JSON format",
                         hint="export this tree as xml (or dot, ascii)")
    if isinstance(node, Retry) and node.attempts < 1:
        raise InputError("a Retry that tries for ever cannot be saved in btplan's JSON format",
                         hint="export this tree as xml")


def node_data(node: Node, with_status: bool) -> dict[str, Any]:
    """One node and its children, fields holding their default left out."""
    data = node_fields(node, with_status)
    if node.children:
        data["children"] = [node_data(c, with_status) for c in node.children]
    return data


def node_fields(node: Node, with_status: bool) -> dict[str, Any]:
    """One node's fields but its children, those holding their default left out."""
    representable(node)
    data: dict[str, Any] = {"type": node.kind}
    name = node.name
    if name and not (isinstance(node, Leaf) and name == leaf_label(node.ident, node.args)):
        data["name"] = name
    if isinstance(node, (Sequence, Fallback)) and node.memory:
        data["memory"] = True
    if isinstance(node, Leaf):
        data["ident"] = node.ident
        if node.args:
            data["args"] = list(node.args)
        if node.ports:
            data["ports"] = list(node.ports)
    if isinstance(node, Retry) and node.attempts != 1:
        data["attempts"] = node.attempts
    if isinstance(node, Timeout) and node.ticks != 1:
        data["ticks"] = node.ticks
    parallel = _parallel()
    if parallel is not None and isinstance(node, parallel):
        if node.success != -1:
            data["success"] = node.success
        if node.failure != 1:
            data["failure"] = node.failure
    if with_status and node.status is not IDLE:
        data["status"] = node.status.value
    return data


def _parallel() -> type[Parallel] | None:
    """The Parallel class if its module was imported; before that no Parallel node exists,
    and trees grown by backchaining (which have none) are written without importing it."""
    module = sys.modules.get("btplan.bt.parallel")
    if module is None:
        return None
    from typing import cast  # only for a tree with Parallel nodes, rare

    return cast("type[Parallel]", module.Parallel)


def tree_data(tree: BehaviorTree, with_status: bool = False) -> dict[str, Any]:
    """The whole tree as `SavedTree.model_dump` would give it (format, version, a name other
    than Main, root); `with_status` adds each node's last status. InputError for a node
    btplan's JSON format cannot hold."""
    data: dict[str, Any] = {"format": FORMAT, "version": VERSION}
    if tree.name != DEFAULT_NAME:
        data["name"] = tree.name
    data["root"] = node_data(tree.root, with_status)
    return data


def dump_json(tree: BehaviorTree, with_status: bool = False) -> str:
    """Indented JSON with short lists (args, ports) kept on one line: what `tree_data`
    gives, laid out as `json.dumps(..., indent=2, ensure_ascii=False)` but for those lists."""
    return "".join(json_pieces(tree, with_status))


def json_pieces(tree: BehaviorTree, with_status: bool = False) -> Iterator[str]:
    """`dump_json`'s text in pieces of about PIECE_PARTS parts each, to be written as
    they come: a large tree's text made whole, with the parts it was joined from and
    its bytes, took four times its size (visit-all p03's tree: 3.7 MB of text, 11 MB
    traced while it was made)."""
    out = [f'{{\n  "format": {_scalar(FORMAT)},\n  "version": {_scalar(VERSION)}']
    if tree.name != DEFAULT_NAME:
        out.append(f',\n  "name": {_scalar(tree.name)}')
    out.append(',\n  "root": ')
    yield from _write_node(tree.root, "  ", with_status, out)
    out.append("\n}\n")
    yield "".join(out)


PIECE_PARTS = 4096
"""Parts (a field, a bracket) gathered before `json_pieces` gives them out as one piece."""


def _write_node(node: Node, indent: str, with_status: bool, out: list[str]) -> Iterator[str]:
    """One node and its children, written into `out` at `indent` (field names are
    plain words, written without a check); what `out` gathered is given out, and `out`
    emptied, once it holds PIECE_PARTS parts."""
    inner = indent + "  "
    before = "{\n"
    for key, value in node_fields(node, with_status).items():
        out.append(f'{before}{inner}"{key}": {_scalar(value)}')
        before = ",\n"
    children = node.children
    if children:
        deeper = inner + "  "
        out.append(f'{before}{inner}"children": [')
        before = "\n"
        for child in children:
            out.append(before + deeper)
            yield from _write_node(child, deeper, with_status, out)
            before = ",\n"
        out.append(f"\n{inner}]")
    out.append(f"\n{indent}}}")
    if len(out) >= PIECE_PARTS:
        yield "".join(out)
        out.clear()


def _scalar(value: Any) -> str:
    """What `json.dumps(value, ensure_ascii=False)` gives. Strings that JSON writes
    unchanged between quotes, integers and lists of such are written here."""
    kind = type(value)
    if kind is str and value.isprintable() and '"' not in value and "\\" not in value:
        return f'"{value}"'
    if kind is int:
        return str(value)
    if value is True:
        return "true"
    if kind is list:
        return f"[{', '.join(map(_scalar, value))}]"
    import json

    return json.dumps(value, ensure_ascii=False)
