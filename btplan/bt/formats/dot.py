"""Graphviz DOT in the paper's notation: `?` Fallback, `→` Sequence, boxes and ellipses.

Actions are boxes and conditions ellipses, as in the paper's figures. Memory variants
carry a star (`?*`, `→*`) as in the BT literature. Node names are the stable ids of
`btplan.bt.trace` (`n0`, `n1`, ... depth first), so a trace can colour the picture.
`ordering=out` keeps children left to right, which is their priority.
"""

from __future__ import annotations

from collections.abc import Collection, Mapping

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import Retry, Timeout
from btplan.bt.leaves import Action, Leaf
from btplan.bt.node import Node
from btplan.bt.parallel import Parallel
from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.tree import BehaviorTree
from btplan.limits import printable

COLOURS: Mapping[Status, str] = {SUCCESS: "#9be09b", FAILURE: "#f4a3a3", RUNNING: "#f7dc6f"}
"""Fill colour per status: green, red, yellow; the status is also in the tooltip."""


def _quote(text: str) -> str:
    text = printable(text)
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def node_label(node: Node) -> str:
    """The text a node shows in the paper's notation."""
    if isinstance(node, Leaf):
        return node.name
    origin = node.origin
    if origin is not None and not isinstance(node, (Sequence, Fallback)):
        attrs = dict(origin.attrs)
        if origin.tag == "SubTree":
            return f"SubTree {attrs.get('ID', '')}"
        if origin.tag in ("Script", "ScriptCondition", "Precondition"):
            code = attrs.get("code", attrs.get("if", ""))
            return f"{origin.tag}: {code if len(code) <= 40 else code[:37] + '...'}"
        return origin.tag + (f" {attrs['name']}" if attrs.get("name") else "")
    star = "*" if getattr(node, "memory", False) else ""
    if isinstance(node, Fallback):
        return "?" + star
    if isinstance(node, Sequence):
        return "→" + star
    if isinstance(node, Parallel):
        return f"⇉ {node.success}/{node.failure}"
    if isinstance(node, Retry):
        return f"Retry {node.attempts}"
    if isinstance(node, Timeout):
        return f"Timeout {node.ticks}"
    return node.kind


def _attributes(node: Node, status: Status | None, halted: bool) -> str:
    attrs = [f"label={_quote(node_label(node))}"]
    styles: list[str] = []
    if isinstance(node, Action):
        attrs.append("shape=box")
    elif isinstance(node, Leaf):
        attrs.append("shape=ellipse")
    elif isinstance(node, (Sequence, Fallback, Parallel)):
        attrs += ["shape=box", "fontsize=18"]
    else:
        attrs.append("shape=box")
        styles.append("rounded")
    tips = [node.name] if node.name and not isinstance(node, Leaf) else []
    if status is not None and status in COLOURS:
        styles.append("filled")
        attrs.append(f'fillcolor="{COLOURS[status]}"')
        tips.append(status.value)
    if halted:
        styles += ["dashed", "bold"]
        tips.append("halted")
    if styles:
        attrs.append(f'style="{",".join(styles)}"')
    if tips:
        attrs.append(f"tooltip={_quote(' '.join(tips))}")
    return ", ".join(attrs)


def dump_dot(tree: BehaviorTree, statuses: Mapping[str, Status] | None = None,
             halted: Collection[str] = ()) -> str:
    """The tree as a DOT digraph.

    `statuses` (by node id, e.g. `TickTrace.statuses()`) fills nodes with their colour;
    `halted` ids (e.g. `TickTrace.halted`) get a bold dashed outline.
    """
    lines = [f"digraph {_quote(tree.name)} {{",
             '  graph [ordering=out, nodesep=0.25, ranksep=0.4];',
             '  node [fontname="Helvetica", fontsize=12, margin="0.08,0.04"];',
             "  edge [arrowhead=none];"]
    nodes = tree.root.walk()
    ids = {id(n): f"n{i}" for i, n in enumerate(nodes)}
    for node in nodes:
        nid = ids[id(node)]
        status = (statuses or {}).get(nid)
        lines.append(f"  {nid} [{_attributes(node, status, nid in halted)}];")
    for node in nodes:
        lines.extend(f"  {ids[id(node)]} -> {ids[id(child)]};" for child in node.children)
    lines.append("}")
    return "\n".join(lines) + "\n"


__all__ = ["COLOURS", "dump_dot", "node_label"]
