"""Tree shapes as nested tuples, easy to compare, and where the shipped domains live."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from btplan.bt import Action, Condition, Fallback, Node, Sequence
from btplan.bt.decorators import Inverter

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


def shape(node: Node) -> Any:
    """('?', ...) for Fallback, ('->', ...) for Sequence, 'pred(args)' or '[Act(args)]'."""
    if isinstance(node, Fallback):
        return ("?", *[shape(c) for c in node.children])
    if isinstance(node, Sequence):
        return ("->", *[shape(c) for c in node.children])
    if isinstance(node, Inverter):
        return ("not", shape(node.children[0]))
    if isinstance(node, Action):
        return f"[{node.name}]"
    if isinstance(node, Condition):
        return node.name
    raise AssertionError(f"unexpected node {node!r}")
