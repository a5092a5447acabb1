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

import re
from collections.abc import Callable, Mapping
from collections.abc import Sequence as Seq
from xml.sax.saxutils import quoteattr

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import ForceFailure, ForceSuccess, Inverter, Retry, Timeout
from btplan.bt.formats.btcpp_catalog import BUILTINS
from btplan.bt.formats.btcpp_files import read_document
from btplan.bt.formats.btcpp_models import ModelEntry, ModelPort, write_models
from btplan.bt.formats.btcpp_read import TICK_MS, ImportedTrees, build_tree
from btplan.bt.leaves import Leaf, leaf_label
from btplan.bt.node import Node
from btplan.bt.parallel import Parallel
from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError

_BAD_ID = re.compile(r"[\s<>&\"'/\\:*?|.]|[\x00-\x1f]")
_PORT = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_RESERVED_PORTS = {"name", "ID", "_autoremap"}
_RESERVED_IDS = {"Root", "root"}
_BUILTIN = set(BUILTINS)


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
           models: dict[str, tuple[str, tuple[str, ...]]],
           uid: Callable[[Node], int] | None = None) -> None:
    """One node and its subtree; with `uid`, as BT.CPP writes a tree it runs: every
    node named (its ID when it has no name of its own) and numbered by `_uid`."""
    pad = "  " * depth
    attrs: list[tuple[str, str]] = []
    if isinstance(node, Leaf):
        _check_leaf(node, models)
        tag = node.ident
        if uid is not None or node.name != leaf_label(node.ident, node.args):
            attrs.append(("name", node.name))
        params = list(zip(node.ports, node.args, strict=True))
    else:
        tag, params = _control(node)
        if node.name or uid is not None:
            attrs.append(("name", node.name or tag))
    if uid is not None:
        attrs.append(("_uid", str(uid(node))))
    attrs.extend(params)
    text = "".join(f" {k}={quoteattr(v)}" for k, v in attrs)
    if not node.children:
        out.append(f"{pad}<{tag}{text}/>")
        return
    out.append(f"{pad}<{tag}{text}>")
    for child in node.children:
        _write(child, depth + 1, out, models, uid)
    out.append(f"{pad}</{tag}>")


def dump_xml(tree: BehaviorTree) -> str:
    """The tree as a BT.CPP v4 document with its TreeNodesModel.

    A tree read from XML is written back node for node, with all the trees and the
    models of its document.
    """
    if tree.imported is not None:
        return _dump_imported(tree, tree.imported)
    if _BAD_ID.search(tree.name) or tree.name in _RESERVED_IDS or not tree.name:
        raise ExportError(f"{tree.name!r} cannot be a BehaviorTree.CPP tree ID")
    models: dict[str, tuple[str, tuple[str, ...]]] = {}
    body: list[str] = []
    _write(tree.root, 2, body, models)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<root BTCPP_format="4" main_tree_to_execute={quoteattr(tree.name)}>',
           f"  <BehaviorTree ID={quoteattr(tree.name)}>", *body, "  </BehaviorTree>",
           *_models_xml(_leaf_models(models)), "</root>"]
    return "\n".join(out) + "\n"


Models = dict[str, tuple[str, tuple[tuple[str, str, str], ...]]]
"""ID -> (kind, its ports as (direction, name, type)): what a TreeNodesModel lists."""


def _leaf_models(models: dict[str, tuple[str, tuple[str, ...]]]) -> Models:
    """The leaves' models: every port an input of type std::string."""
    return {ident: (kind, tuple(("input", p, "std::string") for p in ports))
            for ident, (kind, ports) in models.items()}


def _models_xml(entries: Models) -> list[str]:
    """The TreeNodesModel element's lines, in ID order."""
    out = ["  <TreeNodesModel>"]
    for ident in sorted(entries):
        kind, ports = entries[ident]
        if not ports:
            out.append(f"    <{kind} ID={quoteattr(ident)}/>")
            continue
        out.append(f"    <{kind} ID={quoteattr(ident)}>")
        out.extend(f"      <{d}_port name={quoteattr(n)} type={quoteattr(t)}/>"
                   for d, n, t in ports)
        out.append(f"    </{kind}>")
    out.append("  </TreeNodesModel>")
    return out


def dump_running_xml(tree: BehaviorTree, uid: Callable[[Node], int]) -> str:
    """The tree as BT.CPP describes a tree it runs (its WriteTreeToXML with metadata and
    built-in models, what Groot2 and FileLogger2 read): every node with `name` and
    `_uid`, the tree's `_fullpath`, and a TreeNodesModel with the built-in nodes and
    every leaf ID, in ID order."""
    models: dict[str, tuple[str, tuple[str, ...]]] = {}
    body: list[str] = []
    _write(tree.root, 2, body, models, uid)
    entries: Models = {ident: (spec.kind, tuple((p.direction, p.name, p.type)
                                                for p in spec.ports))
                       for ident, spec in BUILTINS.items()}
    entries.update(_leaf_models(models))
    out = ['<root BTCPP_format="4">',
           f'  <BehaviorTree ID={quoteattr(tree.name or "MainTree")} _fullpath="">', *body,
           "  </BehaviorTree>", *_models_xml(entries), "</root>"]
    return "\n".join(out)


# --- imported documents -------------------------------------------------------------------


def _write_imported(node: Node, depth: int, out: list[str],
                    models: dict[str, tuple[str, tuple[str, ...]]]) -> None:
    """A node read from XML goes back with its tag and attributes as they were read;
    a SubTree without the instance below it (the called tree is written on its own)."""
    origin = node.origin
    if origin is None:
        _write(node, depth, out, models)
        return
    pad = "  " * depth
    text = "".join(f" {k}={quoteattr(v)}" for k, v in origin.attrs)
    children = [] if origin.tag == "SubTree" else node.children
    if not children:
        out.append(f"{pad}<{origin.tag}{text}/>")
        return
    out.append(f"{pad}<{origin.tag}{text}>")
    for child in children:
        _write_imported(child, depth + 1, out, models)
    out.append(f"{pad}</{origin.tag}>")


def _dump_imported(tree: BehaviorTree, imported: ImportedTrees) -> str:
    doc = imported.doc
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<root BTCPP_format="4" main_tree_to_execute={quoteattr(tree.name)}>']
    added: dict[str, tuple[str, tuple[str, ...]]] = {}
    for tree_id, element in doc.trees.items():
        root = tree.root if tree_id == tree.name else imported.roots[tree_id]
        attrs = "".join(f" {k}={quoteattr(v)}" for k, v in element.attrs.items())
        out.append(f"  <BehaviorTree{attrs}>")
        _write_imported(root, 2, out, added)
        out.append("  </BehaviorTree>")
    entries = [e for e in doc.models.values()
               if e.origin != "model" or e.ident in imported.used]
    known = {e.ident for e in entries}
    for ident, (kind, ports) in added.items():
        if ident not in known:
            entries.append(ModelEntry(kind, ident, [
                ModelPort("input", p, (("name", p), ("type", "std::string"))) for p in ports]))
    out += write_models(entries)
    out.append("</root>")
    return "\n".join(out) + "\n"


# --- import -------------------------------------------------------------------------------


def load_xml(text: str, path: str = "<tree>", models: Seq[tuple[str, str]] = (),
             tree_id: str | None = None, strict: bool = False,
             enums: Mapping[str, int] | None = None) -> BehaviorTree:
    """Read a BT.CPP document (version 3 or 4) with its includes.

    `models` are (text, path) pairs of extra TreeNodesModel files; `tree_id` picks the
    tree to execute; `strict` refuses custom nodes no model declares instead of
    inferring them; `enums` are the scripting enums BT.CPP would register in C++.
    Warnings end up in `tree.imported.doc.warnings`.
    """
    doc = read_document(text, path, models, tree_id)
    return build_tree(doc, strict, enums)


__all__ = ["TICK_MS", "ExportError", "dump_xml", "load_xml"]
