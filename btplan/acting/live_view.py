"""The live terminal view of a run: the tree with this tick's statuses, changed facts, agents.

Watching the tree is how a user sees the paper's claim: an undone Pick lights up
again, a helped one is skipped, a blocked path grows a new subtree. Frames are plain
rich renderables built from the run's records, so they can be tested without a
terminal; `LiveView` only puts them on the console it is given.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from types import TracebackType
from typing import Self

from rich.console import Console, Group, RenderableType
from rich.live import Live
from rich.markup import escape
from rich.table import Table
from rich.text import Text
from rich.tree import Tree

from btplan.acting.records import TickRecord
from btplan.bt import Node, Status
from btplan.worlds.agents import Disturbance

STYLE = {
    Status.SUCCESS: "green",
    Status.FAILURE: "red",
    Status.RUNNING: "bold yellow",
    Status.IDLE: "dim",
}
SYMBOL = {"Sequence": "→", "Fallback": "?", "Parallel": "⇉", "Inverter": "!"}
"""The paper's notation: → for Sequence, ? for Fallback."""


def node_label(node: Node, status: Status | None, new: bool) -> Text:
    """One node: its symbol or name, styled by this tick's status (dim if not reached)."""
    kind = node.kind
    if kind == "Action":
        text = f"[{node.name}]"
    elif kind == "Condition":
        text = f"({node.name})"
    else:
        text = SYMBOL.get(kind, kind)
        if node.name and node.name != kind:
            text += f" {node.name}"
    label = Text(text, style=STYLE[status] if status is not None else "dim")
    if status is not None and kind in ("Action", "Condition"):
        label.append(f"  {status.value}", style=STYLE[status])
    if new:
        label.append("  new", style="bold cyan")
    return label


def negated(node: Node) -> Node | None:
    """The condition under an Inverter that holds only it (`not blocks(_, t)`), else None."""
    if node.kind == "Inverter" and len(node.children) == 1 and \
            node.children[0].kind == "Condition":
        return node.children[0]
    return None


def tree_view(root: Node, reached: Mapping[int, Status], old: frozenset[int],
              fold: bool = False) -> Tree:
    """The tree; `reached` maps id(node) to its status this tick, `old` the ids seen before.

    A negated condition is one line, `(not blocks(_, t))`, with the Inverter's own status
    (the condition under it answers the opposite). With `fold`, the children a tick did
    not reach are one line each run of them (`… 12 not reached`): a tree taller than the
    terminal then shows the branch that runs."""

    def label(node: Node) -> Text:
        new = bool(old) and id(node) not in old
        inner = negated(node)
        if inner is None:
            return node_label(node, reached.get(id(node)), new)
        status = reached.get(id(node))
        text = Text(f"(not {inner.name})", style=STYLE[status] if status is not None else "dim")
        if status is not None:
            text.append(f"  {status.value}", style=STYLE[status])
        if new:
            text.append("  new", style="bold cyan")
        return text

    top = Tree(label(root), guide_style="dim")
    stack: list[tuple[Node, Tree]] = [(root, top)]
    while stack:
        node, branch = stack.pop()
        if negated(node) is not None:
            continue
        hidden = 0
        for child in node.children:
            if fold and id(child) not in reached:
                hidden += len(child.walk())
                continue
            if hidden:
                branch.add(Text(f"… {hidden} not reached", style="dim"))
                hidden = 0
            stack.append((child, branch.add(label(child))))
        if hidden:
            branch.add(Text(f"… {hidden} not reached", style="dim"))
    return top


def facts_view(record: TickRecord) -> Text:
    """The facts a tick added (green) and removed (red) on one line; "no change" when none."""
    text = Text()
    for fact in record.added:
        text.append(f"+{fact}  ", style="green")
    for fact in record.removed:
        text.append(f"-{fact}  ", style="red")
    return text if text.plain else Text("no change", style="dim")


def disturbance_view(recent: list[Disturbance]) -> Table:
    """The latest disturbances as a table (tick, agent, what happened), names escaped so
    that brackets in them are not read as rich markup."""
    table = Table(show_header=True, header_style="bold", box=None, pad_edge=False)
    table.add_column("tick", justify="right")
    table.add_column("agent")
    table.add_column("what happened")
    for d in recent:
        table.add_row(str(d.tick), escape(d.agent), escape(d.description))
    return table


def frame(root: Node, reached: Mapping[int, Status], record: TickRecord,
          recent: list[Disturbance], old: frozenset[int] = frozenset(),
          expansions: int = 0, rows: int | None = None) -> RenderableType:
    """One screen: a header line, the facts that changed, the latest disturbances, then
    the tree. Below the tree, a terminal too short cuts only the tree; with `rows` (the
    terminal's height), a tree taller than the room left folds what the tick did not
    reach."""
    header = Text(f"tick {record.tick}  ", style="bold")
    header.append(record.status, style=STYLE.get(Status(record.status), ""))
    header.append(f"   expansions {expansions}", style="bold")
    if record.expansions:
        grown = ", ".join(e.condition for e in record.expansions)
        header.append(f"   (grew at {grown})", style="bold cyan")
    parts: list[RenderableType] = [header, Text("facts: ", style="bold") + facts_view(record)]
    if recent:
        parts.append(Text("disturbances:", style="bold"))
        parts.append(disturbance_view(recent))
    room = None if rows is None else rows - 2 - (2 + len(recent) if recent else 0)
    parts.append(tree_view(root, reached, old,
                           fold=room is not None and len(root.walk()) > room))
    return Group(*parts)


class LiveView:
    """Redraws one frame per tick on a console (standard error, so stdout stays data)."""

    def __init__(self, console: Console, history: int = 6) -> None:
        self.console = console
        self.recent: deque[Disturbance] = deque(maxlen=history)
        self.expansions = 0
        self._seen: frozenset[int] = frozenset()
        self._live = Live(console=console, auto_refresh=False, transient=False,
                          vertical_overflow="crop")

    def __enter__(self) -> Self:
        self._live.__enter__()
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 tb: TracebackType | None) -> None:
        self._live.__exit__(kind, error, tb)

    def show(self, root: Node, reached: Mapping[int, Status], record: TickRecord) -> None:
        """Redraw the frame after a tick; its disturbances join the last few shown, and the
        nodes of this tree are remembered so the next frame can mark what is new."""
        self.recent.extend(record.disturbances)
        self.expansions += len(record.expansions)
        view = frame(root, reached, record, list(self.recent), self._seen, self.expansions,
                     rows=self.console.height)
        self._live.update(view, refresh=True)
        self._seen = frozenset(id(n) for n in root.walk())
