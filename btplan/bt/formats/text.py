"""A terminal view of a tree with rich: one line per node, statuses coloured from a trace.

Nodes a trace did not reach this tick are dimmed, so the view shows at a glance
which branch the tick took and which action is RUNNING. rich is imported when a view
is drawn, not when btplan.bt is imported.
"""

from __future__ import annotations

import io
from collections.abc import Collection, Mapping
from typing import TYPE_CHECKING

from btplan.bt.formats.dot import node_label
from btplan.bt.leaves import Action, Leaf
from btplan.bt.node import Node
from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.tree import BehaviorTree
from btplan.limits import printable

if TYPE_CHECKING:
    from rich.tree import Tree

STYLES: Mapping[Status, str] = {SUCCESS: "green", FAILURE: "red", RUNNING: "yellow"}


def _line(node: Node, status: Status | None, traced: bool, halted: bool) -> str:
    from rich.markup import escape

    if isinstance(node, Action):
        text = escape(f"[{printable(node.name)}]")
    elif isinstance(node, Leaf):
        text = f"({escape(printable(node.name))})"
    else:
        label = printable(node_label(node))
        plain = label.startswith(node.kind) or node.origin is not None and label[:1].isalpha()
        text = escape(label if plain else f"{label} {node.kind}")
        text += f" [italic]{escape(printable(node.name))}[/]" if node.name else ""
    if status in STYLES:
        assert status is not None
        return f"{text} [{STYLES[status]}]{status.value}[/]"
    if halted:
        return f"{text} [bold magenta]HALTED[/]"
    return f"[dim]{text}[/]" if traced else text


def ascii_tree(tree: BehaviorTree, statuses: Mapping[str, Status] | None = None,
               halted: Collection[str] = ()) -> Tree:
    """A rich renderable of the tree, e.g. `ascii_tree(tree, trace.statuses(), trace.halted)`.

    With `statuses` (by node id), unreached nodes are dimmed; `halted` ids are marked.
    """
    from rich.tree import Tree

    nodes = tree.root.walk()
    ids = {id(n): f"n{i}" for i, n in enumerate(nodes)}
    traced = statuses is not None

    def grow(node: Node, parent: Tree | None) -> Tree:
        nid = ids[id(node)]
        line = _line(node, (statuses or {}).get(nid), traced, nid in halted)
        branch = Tree(line, guide_style="dim") if parent is None else parent.add(line)
        for child in node.children:
            grow(child, branch)
        return branch

    return grow(tree.root, None)


def dump_ascii(tree: BehaviorTree, statuses: Mapping[str, Status] | None = None,
               color: bool = False, width: int = 100, halted: Collection[str] = ()) -> str:
    """The view as text; ANSI colours only when `color` is set (never in a pipe by default)."""
    from rich.console import Console

    buffer = io.StringIO()
    console = Console(file=buffer, width=width, force_terminal=color, no_color=not color,
                      color_system="standard" if color else None, highlight=False)
    console.print(ascii_tree(tree, statuses, halted))
    return buffer.getvalue()


__all__ = ["STYLES", "ascii_tree", "dump_ascii"]
